#!/usr/bin/python3
"""pkm's executor in LinuxCNC's servo thread, side by side with LinuxCNC's own motion controller (docs/PERFORMANCE.md).

The same program on the same machine (LinuxCNC's genhexkins geometry, examples/machines/hexapod_genhexkins.yaml,
examples/programs/hexapod_tilt.ngc), alternately:
  - LinuxCNC's trajectory planner and interpolation with its genhexkins kinematics: its own pin
    motion-controller.time (CPU clocks, converted with the CPU's clock rate) every servo period of the run;
  - pkm's pkmexec executing `pkm linuxcnc stream`'s steps of it: its pin pkmexec.exec-time-ns every period.
Prints per-period p50, p99.9 and the worst, in µs, and their ratios. Run from the build's environment:
  PKM_BINARY=build/pkm PKM_SOURCE_DIR=$PWD PKM_KINS_MODULE=build/linuxcnc/pkmkins.so \
  PKM_EXEC_MODULE=build/linuxcnc/pkmexec.so PYTHONPATH=build/python bench/linuxcnc_exec_time.py [ROUNDS]
"""
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.environ["PKM_SOURCE_DIR"], "tests", "linuxcnc"))
from hal_session import FINISHED, HalSession, ended, write_stream  # noqa: E402
from linuxcnc_run import machine_path, program_path, run_linuxcnc  # noqa: E402

MACHINE = machine_path("hexapod_genhexkins.yaml")
PROGRAM = program_path("hexapod_tilt.ngc")


def cpu_hz():
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("cpu MHz"):
                return float(line.split(":")[1]) * 1e6
    raise RuntimeError("no cpu MHz in /proc/cpuinfo")


def genhexkins_us():
    run = run_linuxcnc(MACHINE, PROGRAM, kinematics="genhexkins")
    assert run.returncode == 0 and run.summary.get("finished"), run.log[-2000:]
    coordinated = run.column("coordinated") > 0.5
    return run.column("motion_controller_clocks")[coordinated] / cpu_hz() * 1e6


def pkmexec_us(stream):
    with HalSession(MACHINE) as session:
        feeder = session.feed(stream)
        table = session.record_until(lambda rows: ended(rows, (FINISHED,)), timeout_s=120)
        feeder.wait(timeout=30)
    moving = np.diff(table["tau"], prepend=0.0) > 0
    return table["exec_time_ns"][moving] * 1e-3


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    stream = os.path.join(tempfile.mkdtemp(prefix="pkm-exec-bench-"), "tilt.stream")
    made = write_stream(MACHINE, PROGRAM, stream)
    assert made.returncode == 0, made.stderr
    times = {"genhexkins + tp (motion-controller.time)": [], "pkmexec (exec-time-ns)": []}
    for _ in range(rounds):
        times["genhexkins + tp (motion-controller.time)"].append(genhexkins_us())
        times["pkmexec (exec-time-ns)"].append(pkmexec_us(stream))
    print("| per servo period (µs) | periods | p50 | p99.9 | worst |")
    print("|---|---|---|---|---|")
    stats = {}
    for name, runs in times.items():
        t = np.concatenate(runs)
        stats[name] = (np.percentile(t, 50), np.percentile(t, 99.9), t.max())
        print(f"| {name} | {len(t)} | {stats[name][0]:.2f} | {stats[name][1]:.2f} | {stats[name][2]:.1f} |")
    a, b = stats.values()
    print(f"| ratio pkmexec / genhexkins + tp | | {b[0] / a[0]:.3f} | {b[1] / a[1]:.3f} | {b[2] / a[2]:.3f} |")


if __name__ == "__main__":
    main()
