"""The batch calls release the GIL: another Python thread runs while a batch is inside C++, and two batches run
concurrently from two threads with the results of running them one after the other."""

from __future__ import annotations

import sys
import threading
import time

import numpy as np
import pytest

import pkm
from kinematics_helpers import HEXAPOD_CH5


@pytest.fixture(scope="module")
def hexapod():
    return pkm.Machine.load(HEXAPOD_CH5)


def near_home(machine: pkm.Machine, count: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return machine.home + rng.uniform(-1, 1, (count, 6)) * np.array([20, 20, 20, 0.05, 0.05, 0.05])


class Counter(threading.Thread):
    """A pure-Python thread that counts while it holds the GIL and sleeps 0.1 ms between counts, so that it
    never keeps the GIL from a thread that wants it back."""

    def __init__(self):
        super().__init__(daemon=True)
        self.count = 0
        self.stop = False

    def run(self):
        while not self.stop:
            self.count += 1
            time.sleep(1e-4)


def test_python_runs_while_a_batch_is_in_cpp(hexapod):
    # With a switch interval far longer than a batch, a thread that keeps the GIL is never asked to drop it
    # inside one call: the counter can then only move during the call if the call itself released the GIL.
    # (That bound needs each call to take less than the interval, 60 s; 1e6 poses take well under a second.)
    poses = near_home(hexapod, 1_000_000, seed=1)
    previous = sys.getswitchinterval()
    counter = Counter()
    sys.setswitchinterval(60.0)
    try:
        counter.start()
        while counter.count == 0:
            time.sleep(1e-3)
        moved = False
        for _ in range(10):  # a descheduled counter may miss one call; never all of them
            before = counter.count
            hexapod.ik(poses)
            if counter.count > before:
                moved = True
                break
    finally:
        counter.stop = True
        counter.join()
        sys.setswitchinterval(previous)
    assert moved, "no Python thread ran while Machine.ik was in C++: the GIL was not released"


def test_two_threads_run_batches_concurrently(hexapod):
    first, second = near_home(hexapod, 300_000, seed=2), near_home(hexapod, 300_000, seed=3)
    expected = [hexapod.ik(first), hexapod.ik(second)]
    expected_fk = hexapod.fk(expected[0][:20_000], warm=False)
    results: dict[str, np.ndarray] = {}
    start = threading.Barrier(3)

    def run(name, call):
        start.wait()
        results[name] = call()

    threads = [threading.Thread(target=run, args=("ik1", lambda: hexapod.ik(first))),
               threading.Thread(target=run, args=("ik2", lambda: hexapod.ik(second))),
               threading.Thread(target=run, args=("fk", lambda: hexapod.fk(expected[0][:20_000], warm=False)))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(results["ik1"], expected[0])
    assert np.array_equal(results["ik2"], expected[1])
    assert np.array_equal(results["fk"], expected_fk)
