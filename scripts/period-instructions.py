#!/usr/bin/env python3
"""Instructions per servo period of `pkm interpolate`, counted by valgrind's callgrind.

Wall-clock period times on a shared machine include the operating system (preemption, interrupts, a
hypervisor); an instruction count does not. This runs `pkm interpolate` under callgrind, counting only inside
the per-period computation that the run times (CarrierInterpolator::next and the quantiser), with one dump
per period, and prints the distribution of instructions per period. A bounded maximum close to the median
shows that the code has no slow periods; what remains of the wall-clock maximum is the machine's.

  scripts/period-instructions.py [--pkm build/pkm] [--period-ms 1] [--method carrier-corrected]

Needs valgrind. Runs about 100 times slower than native: the ch5 line at 1 kHz takes a few seconds, at
10 kHz about a minute.
"""
import argparse
import glob
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
QUANTISERS = {
    "carrier-corrected": "pkm::interpolation::DiscretenessCorrector::quantize*",
    "carrier": "pkm::interpolation::RemainderQuantizer::quantize*",
    "exact": "pkm::interpolation::RemainderQuantizer::quantize*",
}


def percentile(sorted_values, fraction):
    rank = max(1, math.ceil(fraction * len(sorted_values)))
    return sorted_values[rank - 1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pkm", default=os.path.join(ROOT, "build", "pkm"))
    parser.add_argument("--program", default=os.path.join(ROOT, "examples/programs/ch5_line.ngc"))
    parser.add_argument("--machine", default=os.path.join(ROOT, "examples/machines/hexapod_ch5.yaml"))
    parser.add_argument("--period-ms", default="1")
    parser.add_argument("--method", default="carrier-corrected", choices=sorted(QUANTISERS))
    args = parser.parse_args()

    with tempfile.TemporaryDirectory(prefix="pkm-period-instructions-") as work:
        period_start = "pkm::interpolation::CarrierInterpolator::next*"
        command = [
            "valgrind", "--tool=callgrind", "--collect-atstart=no",
            f"--toggle-collect={period_start}", f"--toggle-collect={QUANTISERS[args.method]}",
            f"--dump-before={period_start}", f"--callgrind-out-file={work}/periods.%p",
            args.pkm, "interpolate", args.program, "--machine", args.machine, "--method", args.method,
            "--period-ms", args.period_ms, "--out", os.path.join(work, "run"), "--json",
        ]
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        counts = []
        for name in glob.glob(os.path.join(work, "periods.*.*")):
            part = int(name.rsplit(".", 1)[1])
            with open(name) as dump:
                total = next((int(line.split()[1]) for line in dump if line.startswith(("summary:", "totals:"))), 0)
            counts.append((part, total))
    counts.sort()
    # Dump k holds what was counted since dump k-1: period k-1 (the warm-up period among them); the first one
    # is from before any period and the final dump at exit holds the last period.
    per_period = sorted(total for part, total in counts[1:])
    if not per_period:
        sys.exit("no periods counted (was pkm built with symbols for its functions?)")
    print(f"{args.method}, h = {args.period_ms} ms: {len(per_period)} periods (with a warm-up period where the build has one), "
          f"instructions per period p50 {percentile(per_period, 0.5)}, p99 {percentile(per_period, 0.99)}, "
          f"p99.9 {percentile(per_period, 0.999)}, max {per_period[-1]} "
          f"({per_period[-1] / percentile(per_period, 0.5):.2f}× the median)")


if __name__ == "__main__":
    main()
