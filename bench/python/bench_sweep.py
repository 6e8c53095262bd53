#!/usr/bin/env python3
"""pkm.sweep's scaling: a 1e5-point sweep on 1 and on 2 local worker processes (goal ≥ 1.8× on 2).

    PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_sweep.py [--points 100000] [--repeats 5]
        [--machine examples/machines/hexapod_ch5.yaml] [--dask]

Each point is a cheap evaluation: the condition number and δρ of the ch5 hexapod at one pose of a plane grid
round home (one Machine.conditioning call of one pose, so the time is Python's per-point work plus the C++ call).
The times include starting the pool and its workers; the best of --repeats interleaved runs is kept, and the
speed-up a pure-Python load reaches on 2 processes is printed beside it (other work on the cores lowers both). With
--dask the same sweep also runs on a 2-worker LocalCluster (processes, one thread each).
"""

import argparse
import math
import multiprocessing
import os
import sys
import time
from pathlib import Path

import numpy as np

try:
    import pkm
except ImportError as error:
    sys.exit(f"cannot import pkm ({error}): build it with `make python` and run with PYTHONPATH=build/python")

REPOSITORY = Path(__file__).resolve().parents[2]


def conditioning_at(machine, params):
    """δρ and the condition number at (x, y) on the home plane (module level, so that workers import it)."""
    pose = np.array(machine.home, dtype=float)
    pose[0] += params["x_mm"]
    pose[1] += params["y_mm"]
    measures = machine.conditioning(pose)
    return {"delta_rho": measures["delta_rho"], "condition_number": measures["condition_number"]}


def burn(iterations):
    """Pure Python work without pkm: what 2 processes can gain on this computer right now."""
    total = 0
    for i in range(iterations):
        total += i * i
    return total


def machine_scaling(context, iterations=5_000_000):
    """The speed-up of 2 processes over 1 on work that shares nothing (other loads on the cores lower it)."""
    with context.Pool(2) as pool:
        pool.map(burn, [10, 10])
        started = time.perf_counter()
        pool.map(burn, [iterations])
        one = time.perf_counter() - started
        started = time.perf_counter()
        pool.map(burn, [iterations, iterations])
        two = time.perf_counter() - started
    return 2.0 * one / two


def timed(repeats, run):
    best, table = math.inf, None
    for _ in range(repeats):
        started = time.perf_counter()
        table = run()
        best = min(best, time.perf_counter() - started)
    return best, table


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=100_000)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--machine", default=str(REPOSITORY / "examples/machines/hexapod_ch5.yaml"))
    parser.add_argument("--dask", action="store_true", help="also time a 2-worker Dask LocalCluster")
    args = parser.parse_args()

    columns = 100
    rows = max(1, args.points // columns)
    space = {"x_mm": np.linspace(-50.0, 50.0, rows), "y_mm": np.linspace(-50.0, 50.0, columns)}
    points = rows * columns
    print(f"pkm.sweep bench: {points} points, {args.machine}, {len(os.sched_getaffinity(0))} usable cores, "
          f"best of {args.repeats}")

    baseline_before = machine_scaling(multiprocessing.get_context("forkserver"))
    runs = {"serial": dict(executor="serial"), "processes x1": dict(executor="processes", workers=1),
            "processes x2": dict(executor="processes", workers=2)}
    times = dict.fromkeys(runs, math.inf)
    serial = pkm.sweep(conditioning_at, space, base=args.machine, executor="serial", table="numpy")
    for _ in range(args.repeats):  # interleaved, so that a burst of other load on the cores hits every variant
        for name, options in runs.items():
            seconds, table = timed(1, lambda: pkm.sweep(conditioning_at, space, base=args.machine, table="numpy",
                                                        **options))
            assert np.array_equal(table, serial), f"{name} changed the table"
            times[name] = min(times[name], seconds)
    if args.dask:
        import distributed
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as client:
            seconds, table = timed(args.repeats, lambda: pkm.sweep(conditioning_at, space, base=args.machine,
                                                                   executor="dask", scheduler=client,
                                                                   table="numpy"))
            assert np.array_equal(table, serial), "Dask changed the table"
            times["dask x2"] = seconds
    for name, seconds in times.items():
        print(f"  {name:14s} {seconds:7.3f} s  {points / seconds / 1e3:8.1f} k points/s  "
              f"{seconds / points * 1e6:6.2f} µs/point")
    speedup = times["processes x1"] / times["processes x2"]
    print(f"speed-up of 2 worker processes over 1: {speedup:.2f}x (goal >= 1.8x); this computer's own for "
          f"work sharing nothing, before and after: {baseline_before:.2f}x, "
          f"{machine_scaling(multiprocessing.get_context('forkserver')):.2f}x")


if __name__ == "__main__":
    main()
