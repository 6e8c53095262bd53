#!/usr/bin/env python3
"""Per-period compute time of two `pkm` builds, run alternately (before and after in one run).

On a shared machine the load changes from minute to minute, so the two binaries are run in turns, A B A B …,
on the same program and period, and each run's distribution (summary.json: period_time_us_p50, _p99, _p99_9,
_max, period_time_over_10us) is printed, then the median of every figure over the runs of each binary.

  scripts/period-time-compare.py --before /tmp/pkm-before/build/pkm --after build/pkm [--runs 5] [--period-ms 1 0.1]

Both binaries must report the distribution (the commit that added it or later).
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FIGURES = ["period_time_us_p50", "period_time_us_p99", "period_time_us_p99_9", "period_time_us_max",
           "period_time_over_10us", "period_time_count"]


def run_once(pkm, args, period_ms, out):
    command = [pkm, "interpolate", args.program, "--machine", args.machine, "--method", args.method,
               "--period-ms", str(period_ms), "--out", out, "--json"]
    summary = json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)
    return [summary[key] for key in FIGURES]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", required=True)
    parser.add_argument("--after", required=True)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--period-ms", type=float, nargs="+", default=[1.0, 0.1])
    parser.add_argument("--method", default="carrier-corrected")
    parser.add_argument("--program", default=os.path.join(ROOT, "examples/programs/ch5_line.ngc"))
    parser.add_argument("--machine", default=os.path.join(ROOT, "examples/machines/hexapod_ch5.yaml"))
    args = parser.parse_args()

    print("binary  period_ms  p50_us  p99_us  p99.9_us  max_us  over_10us  periods")
    with tempfile.TemporaryDirectory(prefix="pkm-period-time-") as work:
        for period_ms in args.period_ms:
            results = {"before": [], "after": []}
            for _ in range(args.runs):
                for name in ("before", "after"):
                    pkm = getattr(args, name)
                    figures = run_once(pkm, args, period_ms, os.path.join(work, name))
                    results[name].append(figures)
                    print(f"{name:7} {period_ms:9g} " + " ".join(f"{v:8.2f}" if isinstance(v, float) else f"{v:8d}"
                                                           for v in figures))
            for name in ("before", "after"):
                medians = [statistics.median(column) for column in zip(*results[name])]
                print(f"median {name:7} h = {period_ms:g} ms: " +
                      ", ".join(f"{key[len('period_time_'):]} {value:.2f}" for key, value in zip(FIGURES, medians)))


if __name__ == "__main__":
    main()
