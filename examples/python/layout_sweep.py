#!/usr/bin/env python3
"""A layout sweep with pkm.sweep: which platform/base radius ratio of a ch5-like hexapod keeps the worst error
amplification δρ over a work volume lowest?

    PYTHONPATH=build/python /usr/bin/python3 examples/python/layout_sweep.py --out out/ [--quick]
        [--executor serial|processes|dask] [--workers N] [--scheduler tcp://host:8786]

The variants are pkm.layouts.hexapod(400, 400·ratio, height_mm=550, tool_mm=150) for each ratio and platform-pair
separation δ (ratio 0.5 at δ = 0 is examples/machines/hexapod_ch5.yaml's geometry). The work volume is a grid
round home: x, y ±50 mm, z ±50 mm, tilts a, b ±5° (243 poses, or 108 with --quick); each variant's δρ over it
comes from one batch call of Machine.conditioning. A pose a variant cannot reach makes its worst δρ infinite. Writes
layout_sweep.png and layout_sweep.json and prints the best ratio per δ.
"""

import itertools
import math

import numpy as np

from example_support import arguments, import_pkm, pyplot, sweep_options, write_outputs

pkm = import_pkm()
from pkm import layouts  # noqa: E402 (after the import check)

BASE_RADIUS_MM, HEIGHT_MM, TOOL_MM = 400.0, 550.0, 150.0
HOME = np.array([0.0, 0.0, HEIGHT_MM + TOOL_MM, 0.0, 0.0, 0.0])


def work_volume(per_axis: int) -> np.ndarray:
    """The grid of poses round home: x, y, z ±50 mm and the tilts a, b ±5° (3 values each), per_axis on x, y."""
    span = np.linspace(-50.0, 50.0, per_axis)
    tilts = np.radians([-5.0, 0.0, 5.0])
    offsets = [(x, y, z, a, b, 0.0) for x, y, z, a, b in itertools.product(span, span, [-50.0, 0.0, 50.0], tilts,
                                                                            tilts)]
    return HOME + np.array(offsets)


def ch5_like(platform_ratio: float, platform_separation_deg: float = 0.0) -> dict:
    """The sweep's base: a variant's machine dict from its two parameters (module level, so workers import it)."""
    return layouts.hexapod(BASE_RADIUS_MM, BASE_RADIUS_MM * platform_ratio,
                           platform_separation_deg=platform_separation_deg, height_mm=HEIGHT_MM, tool_mm=TOOL_MM)


def worst_delta_rho(machine, params):
    """The sweep's evaluate: the worst and mean δρ over the work volume (its size from the point's parameters)."""
    delta_rho = machine.conditioning(work_volume(params["per_axis"]))["delta_rho"]
    unreachable = int(np.isnan(delta_rho).sum())
    return {"worst_delta_rho": math.inf if unreachable else float(delta_rho.max()),
            "mean_delta_rho": float(np.nanmean(delta_rho)) if unreachable < delta_rho.size else math.nan,
            "unreachable": unreachable}


def main():
    args = arguments(__doc__.splitlines()[0])
    ratios = np.linspace(0.1, 0.9, 9 if args.quick else 81)
    separations = [0.0, 30.0] if args.quick else [0.0, 15.0, 30.0, 45.0]
    space = {"platform_separation_deg": separations, "platform_ratio": ratios, "per_axis": [2 if args.quick else 3]}
    table = pkm.sweep(worst_delta_rho, space, base=ch5_like, table="numpy", **sweep_options(args))

    plt = pyplot()
    figure, axes = plt.subplots(figsize=(7, 5))
    best = {}
    for separation in separations:
        rows = table[table["platform_separation_deg"] == separation]
        index = int(np.argmin(rows["worst_delta_rho"]))
        best[separation] = rows[index]
        line, = axes.plot(rows["platform_ratio"], rows["worst_delta_rho"], "o-", markersize=3,
                          label=f"δ = {separation:g}°: best ratio {rows['platform_ratio'][index]:.3f}")
        axes.plot(rows["platform_ratio"][index], rows["worst_delta_rho"][index], "*", markersize=14,
                  color=line.get_color())
        print(f"δ {separation:4.0f}°: best platform/base ratio {rows['platform_ratio'][index]:.3f} "
              f"(worst δρ {rows['worst_delta_rho'][index]:.4f}, mean {rows['mean_delta_rho'][index]:.4f}); "
              f"unreachable variants {int(np.isinf(rows['worst_delta_rho']).sum())} of {len(rows)}")
    axes.set_xlabel(f"platform radius / base radius ({BASE_RADIUS_MM:g} mm)")
    axes.set_ylabel("worst δρ over the work volume (mm/mm)")
    axes.set_title("ch5-like hexapod: x, y, z ±50 mm, a, b ±5° round home")
    axes.grid(True, alpha=0.3)
    axes.legend()
    finite = table["worst_delta_rho"][np.isfinite(table["worst_delta_rho"])]
    if finite.size:
        axes.set_ylim(0.9 * finite.min(), min(finite.max(), 4.0 * finite.min()) * 1.05)
    summary = {"ratios": ratios.tolist(), "separations_deg": separations,
               "poses_per_variant": int(work_volume(space["per_axis"][0]).shape[0]),
               "worst_delta_rho": {f"{s:g}": table["worst_delta_rho"][table["platform_separation_deg"] == s].tolist()
                                   for s in separations},
               "best_ratio": {f"{s:g}": float(row["platform_ratio"]) for s, row in best.items()},
               "best_worst_delta_rho": {f"{s:g}": float(row["worst_delta_rho"]) for s, row in best.items()}}
    write_outputs(args.out, "layout_sweep", figure, summary)


if __name__ == "__main__":
    main()
