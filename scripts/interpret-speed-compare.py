#!/usr/bin/python3
"""pkm's G-code interpreter against LinuxCNC's rs274 on the same programs: wall time and peak memory.

Writes three programs into a scratch folder:
  cam      a 1 000 000-line CAM-like program (scripts/gen-long-program.py: short G1 lines, tangent arcs, feeds)
  while    a 100 000-iteration O-word while loop with a G1 move in every iteration
  while0   the same loop without the move (the expression evaluator and the control flow alone)
and runs each, one after the other, under
  rs274 -g PROGRAM > /dev/null               (LinuxCNC's standalone interpreter printing its canonical calls)
  pkm interpret --count PROGRAM               (pkm's interpretation alone: only the summary is printed)
  pkm interpret --json PROGRAM > /dev/null    (and with every move printed, as the conformance check reads it)
Prints a table of wall times, peak resident memory (the child's ru_maxrss) and the pkm/rs274 time ratio.
A pkm without --count (older than this script) is timed with --json only.

Usage: scripts/interpret-speed-compare.py [--pkm build/pkm] [--rs274 rs274] [--lines 1000000]
                                          [--iterations 100000] [--keep DIR]
Standard library only; Debian's /usr/bin/python3.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def while_program(iterations, motion):
    body = "G1 X[#1 MOD 100] F1000\n" if motion else ""
    return (f"#1=0\no100 while [#1 LT {iterations}]\n{body}#1=[#1+1]\no100 endwhile\nM2\n")


def write_programs(folder, lines, iterations):
    cam = folder / "cam.ngc"
    subprocess.run([sys.executable, str(ROOT / "scripts" / "gen-long-program.py"), str(cam), str(lines)],
                   check=True, stdout=subprocess.DEVNULL)
    programs = [("cam", cam, f"{lines} lines")]
    for name, motion in (("while", True), ("while0", False)):
        path = folder / f"{name}.ngc"
        path.write_text(while_program(iterations, motion))
        programs.append((name, path, f"{iterations} iterations" + ("" if motion else ", no motion")))
    return programs


def timed(command):
    """(wall seconds, peak RSS in MB, exit code) of one child, its output thrown away."""
    start = time.perf_counter()
    with open(os.devnull, "wb") as null:
        child = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=null, stderr=null)
        # wait4 rather than wait: the child's own rusage, so ru_maxrss is this run's peak (in KB on Linux)
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - start
    return wall, usage.ru_maxrss / 1024.0, child.returncode


def has_count(pkm):
    try:
        text = subprocess.run([pkm, "interpret", "--help"], capture_output=True, text=True).stdout
    except OSError:
        sys.exit(f"interpret-speed-compare: cannot run {pkm} (make build, or give --pkm)")
    return "--count" in text


def measure(programs, rs274, pkm):
    runs = [("rs274 -g", lambda p: [rs274, "-g", str(p)])]
    if has_count(pkm):
        runs.append(("pkm interpret --count", lambda p: [pkm, "interpret", "--count", str(p)]))
    runs.append(("pkm interpret --json", lambda p: [pkm, "interpret", "--json", str(p)]))
    rows = []
    for name, path, what in programs:
        reference = None
        for label, command in runs:
            wall, rss_mb, code = timed(command(path))
            if reference is None:
                reference = wall
            ratio = wall / reference if reference > 0 else float("nan")
            rows.append((f"{name} ({what})", label, wall, rss_mb, ratio, code))
            print(f"  {name:<7} {label:<22} {wall:8.2f} s {rss_mb:8.1f} MB", file=sys.stderr, flush=True)
    return rows


def print_table(rows):
    print(f"{'program':<38} {'interpreter':<22} {'wall s':>8} {'peak MB':>8} {'/ rs274':>8}  exit")
    for program, label, wall, rss_mb, ratio, code in rows:
        shown_ratio = f"{ratio:8.2f}" if code == 0 else f"{'-':>8}"  # a failed run's time compares nothing
        print(f"{program:<38} {label:<22} {wall:8.2f} {rss_mb:8.1f} {shown_ratio}  {code}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pkm", default=str(ROOT / "build" / "pkm"))
    parser.add_argument("--rs274", default="rs274")
    parser.add_argument("--lines", type=int, default=1_000_000, help="lines of the CAM-like program")
    parser.add_argument("--iterations", type=int, default=100_000, help="iterations of the while loops")
    parser.add_argument("--keep", help="write the programs into this folder and keep them")
    arguments = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="pkm-speed-") as scratch:
        folder = Path(arguments.keep) if arguments.keep else Path(scratch)
        folder.mkdir(parents=True, exist_ok=True)
        programs = write_programs(folder, arguments.lines, arguments.iterations)
        rows = measure(programs, arguments.rs274, arguments.pkm)
    print_table(rows)
    # A run that failed is in the table with its exit code; the comparison means nothing then.
    return 1 if any(row[5] != 0 for row in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
