"""Batch IK from Python against the C++ loop, and the Python overhead of one call.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_batch.py [--poses 1000000] [--machine FILE]

Measures, in one run on this computer:
  - Machine.ik on N poses near home (all cores, and one thread) in poses/s;
  - the same C++ loop on one thread without Python (pkm._pkm._ik_loop_seconds: the row kernel of Machine.ik
    with its range check, timed inside C++), and `pkm bench kinematics`' IK time when PKM_BINARY is set;
  - the time of one Machine.ik call on a (6,) pose, and what Python adds to the C++ time of one pose.
Each figure is the best of --repeats runs (the least disturbed by other work on the machine).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import pkm

ROOT = Path(__file__).resolve().parents[2]


def best_seconds(call, repeats: int) -> float:
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - start)
    return best


def poses_near_home(machine: pkm.Machine, count: int, seed: int = 1) -> np.ndarray:
    """Poses within ±20 mm and ±10° of home (the ranges of `pkm bench kinematics`), all reachable."""
    rng = np.random.default_rng(seed)
    ranges = np.array([20, 20, 20, np.radians(10), np.radians(10), np.radians(10)]) * np.array(machine.controlled_axes)
    return machine.home + rng.uniform(-1, 1, (count, 6)) * ranges


def single_call_seconds(call, pose, calls: int, repeats: int) -> float:
    def loop():
        for _ in range(calls):
            call(pose)
    return best_seconds(loop, repeats) / calls


def no_op_call_seconds(calls: int, repeats: int) -> float:
    """A pybind11 call that does (almost) nothing, in the same kind of loop: the floor of any call."""
    call = pkm.get_threads

    def loop():
        for _ in range(calls):
            call()
    return best_seconds(loop, repeats) / calls


def cli_ik_ns(machine_file: Path) -> float | None:
    binary = os.environ.get("PKM_BINARY")
    if not binary:
        return None
    out = subprocess.run([binary, "bench", "kinematics", "--machine", str(machine_file), "--ik-poses", "1000000",
                          "--path-poses", "10", "--cold-poses", "10", "--json"],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)["ik_ns_per_pose"]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--machine", type=Path, default=ROOT / "examples" / "machines" / "hexapod_ch5.yaml")
    parser.add_argument("--poses", type=int, default=1_000_000)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--calls", type=int, default=200_000, help="single calls per overhead measurement")
    args = parser.parse_args()

    machine = pkm.Machine.load(args.machine)
    poses = poses_near_home(machine, args.poses)
    assert not np.isnan(machine.ik(poses, errors="nan")).any()
    n = args.poses
    threads = pkm.get_threads()

    batch_all = best_seconds(lambda: machine.ik(poses), args.repeats)
    reused = np.empty((n, machine.actuator_count))
    batch_reused = best_seconds(lambda: machine.ik(poses, out=reused), args.repeats)
    pkm.set_threads(1)
    try:
        batch_one = best_seconds(lambda: machine.ik(poses), args.repeats)
    finally:
        pkm.set_threads(None)
    cpp_loop = min(pkm._pkm._ik_loop_seconds(machine, poses) for _ in range(args.repeats))
    cpp_loop_unchecked = min(pkm._pkm._ik_loop_seconds(machine, poses, check_limits=False)
                             for _ in range(args.repeats))
    cli_ns = cli_ik_ns(args.machine)

    pose = np.ascontiguousarray(poses[0])
    one_call = single_call_seconds(machine.ik, pose, args.calls, args.repeats)
    row_call = single_call_seconds(machine.ik, pose[None, :], args.calls, args.repeats)
    list_call = single_call_seconds(machine.ik, pose.tolist(), args.calls // 4, args.repeats)
    empty_call = no_op_call_seconds(args.calls, args.repeats)
    cpp_per_pose = cpp_loop / n

    print(f"{machine.name} ({args.machine.name}), {n} poses within ±20 mm / ±10° of home, "
          f"{threads} threads, best of {args.repeats}, Python {sys.version.split()[0]}, numpy {np.__version__}")
    print()
    print(f"{'batch IK':44s} {'M poses/s':>10s} {'ns/pose':>9s} {'vs C++ loop':>12s}")
    rows = [("Machine.ik, all threads", batch_all),
            ("Machine.ik(out=reused array), all threads", batch_reused),
            ("Machine.ik, pkm.set_threads(1)", batch_one),
            ("C++ loop of Machine.ik, 1 thread", cpp_loop),
            ("C++ loop without the range check, 1 thread", cpp_loop_unchecked)]
    if cli_ns is not None:
        rows.append(("pkm bench kinematics (IK), 1 thread", cli_ns * 1e-9 * n))
    for label, seconds in rows:
        print(f"{label:44s} {n / seconds / 1e6:10.2f} {seconds / n * 1e9:9.1f} {cpp_loop / seconds:11.2f}x")
    print()
    print(f"{'one call':44s} {'µs/call':>10s} {'Python µs':>10s}")
    for label, seconds in [("Machine.ik(pose), pose (6,) float64", one_call),
                           ("Machine.ik(poses), poses (1, 6) float64", row_call),
                           ("Machine.ik(list of 6 floats)", list_call)]:
        print(f"{label:44s} {seconds * 1e6:10.3f} {(seconds - cpp_per_pose) * 1e6:10.3f}")
    print(f"{'C++ IK of one pose (from the loop)':44s} {cpp_per_pose * 1e6:10.3f}")
    print(f"{'a pybind11 call doing nothing (get_threads)':44s} {empty_call * 1e6:10.3f}")
    print()
    print(f"Python overhead of one ik call: {(one_call - cpp_per_pose) * 1e6:.3f} µs (goal ≤ 1 µs); "
          f"batch speed: {n / batch_all / 1e6:.1f} M poses/s, {n / batch_reused / 1e6:.1f} M poses/s into a reused "
          f"array (goal ≥ 20 M poses/s on 2 cores), {cpp_loop / batch_all:.2f}x / {cpp_loop / batch_reused:.2f}x "
          f"the one-thread C++ loop")
    return 0


if __name__ == "__main__":
    sys.exit(main())
