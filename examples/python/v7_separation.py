#!/usr/bin/env python3
"""The separation study of Smirnov 2019, §3.5.1 (Table 2): on the chapter-3 hexapod, the tool runs
round a circle of R 50 mm at z 700 mm; the sum over its 1° steps of the largest strut increment, Σ max_j |ΔL_j|
(machining time at the struts' speed limit), against the separation δ of the platform joint pairs, with the
platform angles held at zero and chosen by the increment law (greedy, all three angles within ±10°).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/v7_separation.py --out out/ [--quick]

Writes v7_separation.png and v7_separation.json (the sums per δ) and prints the table. The machines are
pkm.layouts.hexapod(500, 300, platform_separation_deg=δ), i.e. examples/machines/hexapod_ch3.yaml at δ = 0 and
hexapod_ch3_delta30.yaml at 30°; the held-constant sum is also computed here from batch IK, independently of the
optimiser.
"""

import functools
import math

import numpy as np

from example_support import REPOSITORY, arguments, import_pkm, pyplot, sweep_options, write_outputs

pkm = import_pkm()
from pkm import layouts  # noqa: E402 (after the import check)

PROGRAM = str(REPOSITORY / "examples/programs/hexapod_circle.ngc")
CIRCLE_RADIUS_MM, CIRCLE_Z_MM, STEPS = 50.0, 700.0, 360
# One degree of arc per optimised point (a hair more, so that rounding cannot make it 361 parts).
STEP_MM = 2.0 * math.pi * CIRCLE_RADIUS_MM / STEPS * (1.0 + 1e-9)
# Table 2 of Smirnov 2019 (δ = 0: the text's 148 mm held constant, 145 mm optimised).
PRINTED_TABLE2 = {0: (148.0, 145.0), 10: (139.0, 130.0), 20: (132.0, 107.0), 30: (126.0, 85.0)}


def constant_angle_sum_mm(machine) -> float:
    """Σ over the circle's 1° steps of max_j |ΔL_j| with the platform level: batch IK of the 361 points."""
    turn = np.radians(np.arange(STEPS + 1, dtype=float))
    poses = np.zeros((STEPS + 1, 6))
    poses[:, 0] = CIRCLE_RADIUS_MM * np.cos(turn)
    poses[:, 1] = CIRCLE_RADIUS_MM * np.sin(turn)
    poses[:, 2] = CIRCLE_Z_MM
    lengths = machine.ik(poses)
    return float(np.abs(np.diff(lengths, axis=0)).max(axis=1).sum())


def increment_sums(machine, params):
    """The sweep's evaluate: both sums for one separation (module level, so that worker processes import it)."""
    run = pkm.optimize(machine, PROGRAM, "increment", free="all", bounds_deg=(-10.0, 10.0), step_mm=STEP_MM,
                       solver="greedy")
    return {"const_sum_mm": float(run["summary"]["const_sum_mm"]),
            "greedy_sum_mm": float(run["summary"]["opt_sum_mm"]),
            "ik_const_sum_mm": constant_angle_sum_mm(machine),
            "largest_angle_deg": float(np.degrees(np.abs(run["free_rad"]).max()))}


def main():
    args = arguments(__doc__.splitlines()[0])
    if not hasattr(pkm, "optimize"):
        raise SystemExit("v7_separation: this pkm build has no pkm.optimize (the pipeline bindings); "
                         "rebuild with `make python`")
    separations = [0.0, 15.0, 30.0] if args.quick else [2.5 * k for k in range(13)]
    table = pkm.sweep(increment_sums, {"platform_separation_deg": separations},
                      base=functools.partial(layouts.hexapod, 500.0, 300.0), table="numpy", **sweep_options(args))

    delta = table["platform_separation_deg"]
    const, greedy = table["const_sum_mm"], table["greedy_sum_mm"]
    print(" delta_deg  const_mm  greedy_mm  ratio  max|angle|_deg   Smirnov 2019 Table 2 (const, opt)")
    for row in table:
        printed = PRINTED_TABLE2.get(int(row["platform_separation_deg"]))
        printed_text = f"{printed[0]:.0f}, {printed[1]:.0f}" if printed and row["platform_separation_deg"] % 10 == 0 else ""
        print(f"{row['platform_separation_deg']:10.1f} {row['const_sum_mm']:9.2f} {row['greedy_sum_mm']:10.2f} "
              f"{row['const_sum_mm'] / row['greedy_sum_mm']:6.2f} {row['largest_angle_deg']:15.2f}   {printed_text}")

    plt = pyplot()
    figure, (sums, ratio) = plt.subplots(2, 1, figsize=(7, 7), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    sums.plot(delta, const, "o-", color="tab:gray", label="angles held at 0 (pkm)")
    sums.plot(delta, greedy, "o-", color="tab:blue", label="increment law, greedy, 3 angles ±10° (pkm)")
    printed_delta = sorted(PRINTED_TABLE2)
    sums.plot(printed_delta, [PRINTED_TABLE2[d][0] for d in printed_delta], "s", mfc="none", color="tab:gray",
              label="Smirnov 2019, Table 2, constant")
    sums.plot(printed_delta, [PRINTED_TABLE2[d][1] for d in printed_delta], "^", mfc="none", color="tab:blue",
              label="Smirnov 2019, Table 2, optimal")
    sums.set_ylabel("Σ max_j |ΔL_j| along the circle (mm)")
    sums.set_title("Table 2 hexapod, R 50 mm circle at z 700 mm, 1° steps")
    sums.grid(True, alpha=0.3)
    sums.legend()
    ratio.plot(delta, const / greedy, "o-", color="tab:green")
    ratio.set_xlabel("separation δ of the platform joint pairs (deg)")
    ratio.set_ylabel("time ratio")
    ratio.grid(True, alpha=0.3)
    summary = {"separation_deg": delta.tolist(), "const_sum_mm": const.tolist(), "greedy_sum_mm": greedy.tolist(),
               "ik_const_sum_mm": table["ik_const_sum_mm"].tolist(),
               "largest_angle_deg": table["largest_angle_deg"].tolist(), "step_mm": STEP_MM}
    write_outputs(args.out, "v7_separation", figure, summary)


if __name__ == "__main__":
    main()
