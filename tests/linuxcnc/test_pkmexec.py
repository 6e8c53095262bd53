"""pkm's planned motion executed in LinuxCNC's servo thread by pkm's component pkmexec (docs/linuxcnc.md).

`pkm linuxcnc stream` plans a program within the execution headroom and interpolates it to whole drive steps;
linuxcnc/pkm_feed.py streams it into pkmexec while it runs; LinuxCNC's sampler records pkmexec's pins every
servo period. At 100 % feed the drives' counts must be pkm's steps themselves, period by period; under feed
holds and overrides the set points must stay within the drives' limits and the program must end where it was
planned to; a stream that leaves the drives' range stops before it, naming the line.
"""
import os
import random
import shutil
import tempfile

import numpy as np
import pkm
import pytest

from hal_session import (ABORTED, FINISHED, REFUSED, RUNNING, STOPPED_AT_LIMIT, HalSession, ended,
                         rtapi_processes, stream_periods, write_stream)
from linuxcnc_run import machine_path, program_path

MACHINE = machine_path("hexapod_ch5.yaml")
PERIOD_S = 1e-3
SPEED_MM_S, ACCEL_MM_S2 = 100.0, 2000.0  # the ch5 hexapod's limits (examples/machines/hexapod_ch5.yaml)


@pytest.fixture
def work():
    directory = tempfile.mkdtemp(prefix="pkm-exec-test-")
    yield directory
    shutil.rmtree(directory, ignore_errors=True)


def streamed(work, program, out_dir=None):
    path = os.path.join(work, os.path.basename(program) + ".stream")
    made = write_stream(MACHINE, program_path(program), path, out_dir)
    assert made.returncode == 0, made.stderr
    return path


def released(table):
    """The periods in which pkmexec moved on through the program (τ advanced)."""
    return np.diff(table["tau"], prepend=0.0) > 0


def assert_within_limits(table):
    """Speed and acceleration of every drive's set point by differences over the period (mm)."""
    set_points = np.column_stack([table[f"set_point_{j}"] for j in range(6)])
    speed = np.abs(np.diff(set_points, axis=0)) / PERIOD_S
    accel = np.abs(np.diff(set_points, n=2, axis=0)) / PERIOD_S**2
    assert speed.max() <= SPEED_MM_S * (1 + 1e-6), speed.max()
    assert accel.max() <= ACCEL_MM_S2 * (1 + 1e-6), accel.max()
    # The whole steps within one step of the set point: the interpolator's own steps (which choose the step
    # below or above the ideal value to keep the contour error small) on the plan's grid, rounded between.
    counts = np.column_stack([table[f"counts_{j}"] for j in range(6)]) * 0.001
    assert np.abs(counts - set_points).max() <= 0.001 + 1e-9


@pytest.mark.parametrize("program", ["ch5_line.ngc", "pocket.ngc"])
def test_the_drives_get_pkms_steps_period_by_period(work, program):
    out_dir = os.path.join(work, "interpolation")
    path = streamed(work, program, out_dir)
    start, positions, _, lines = stream_periods(path)
    steps_csv = np.loadtxt(os.path.join(out_dir, "steps.csv"), delimiter=",", skiprows=1, ndmin=2)
    assert np.array_equal(steps_csv[:, 9:15].astype(np.int64), positions)  # the stream is pkm's steps.csv
    with HalSession(MACHINE) as session:
        feeder = session.feed(path)
        table = session.record_until(lambda rows: ended(rows), timeout_s=len(positions) * PERIOD_S + 60)
        assert feeder.wait(timeout=30) == 0, feeder.stderr.read()
    assert table["state"][-1] == FINISHED
    rows = released(table)
    counts = np.column_stack([table[f"counts_{j}"][rows] for j in range(6)])
    # Every period once, in order, at τ = 1, 2, 3, …: the planned steps themselves.
    assert np.array_equal(table["tau"][rows], np.arange(1, len(positions) + 1))
    assert np.array_equal(counts, positions)
    assert np.array_equal(table["line"][rows], lines)
    before = table["tau"] == 0
    assert (np.abs(np.column_stack([table[f"counts_{j}"][before] for j in range(6)]) - start) <= 1).all()
    # Where the emitted steps put the tool (pkm's FK of the counts) is where pkm measured its contour error
    # (contour.csv, 6 decimals), so the contour error on the controller is pkm's own figure.
    machine = pkm.Machine.load(MACHINE)
    tool = machine.fk(counts * 0.001)[:, :3]
    contour = np.loadtxt(os.path.join(out_dir, "contour.csv"), delimiter=",", skiprows=1, ndmin=2)
    assert np.abs(tool - contour[:, 4:7]).max() <= 6e-7
    assert rtapi_processes() == []


def test_feed_holds_at_random_periods_keep_the_limits_and_end_where_planned(work):
    path = streamed(work, "ch5_line.ngc")
    _, positions, _, _ = stream_periods(path)
    rng = random.Random(41)
    toggles = {"next": 0.0, "held": False}

    def operator(session):
        now = len(session.rows) * PERIOD_S
        if now >= toggles["next"] and len(session.rows) > 0 and session.rows[-1][12] != FINISHED:
            toggles["held"] = not toggles["held"]
            session.setp("pkmexec.feed-hold", int(toggles["held"]))
            toggles["next"] = now + rng.uniform(0.05, 0.6)

    with HalSession(MACHINE) as session:
        feeder = session.feed(path)
        table = session.record_until(lambda rows: ended(rows, (FINISHED,)), timeout_s=60, every=operator)
        session.setp("pkmexec.feed-hold", 0)
        assert feeder.wait(timeout=30) == 0
    assert table["factor"].min() == 0.0  # it did stop at least once
    assert_within_limits(table)
    final = [table[f"counts_{j}"][-1] for j in range(6)]
    assert final == list(positions[-1])


def random_program(path, seed):
    """A short CAM-like program: G1 lines and G2/G3 arcs at changing feeds, small tilts, within ±40 mm."""
    rng = random.Random(seed)
    x = y = 0.0
    lines = ["G21 G90 G17 G94", "G1 X0 Y0 Z0 F1500"]
    for _ in range(10):
        feed = rng.choice([1800, 3000, 4800])
        nx, ny = (max(-40.0, min(40.0, v + rng.uniform(-15, 15))) for v in (x, y))
        if rng.random() < 0.3:
            radius = max(abs(nx - x), abs(ny - y)) + rng.uniform(2, 10)
            lines.append(f"{rng.choice(['G2', 'G3'])} X{nx:.3f} Y{ny:.3f} R{radius:.3f} F{feed}")
        else:
            tilt = f" A{rng.uniform(-4, 4):.2f} B{rng.uniform(-4, 4):.2f}" if rng.random() < 0.3 else ""
            lines.append(f"G1 X{nx:.3f} Y{ny:.3f} Z{rng.uniform(-5, 5):.3f}{tilt} F{feed}")
        x, y = nx, ny
    lines += ["G1 X0 Y0 Z0 A0 B0 F3000", "M2"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


@pytest.mark.parametrize("seed", [1, 2])
def test_holds_and_overrides_at_random_periods_of_random_programs_keep_the_limits(work, seed):
    program = os.path.join(work, f"random{seed}.ngc")
    random_program(program, seed)
    path = os.path.join(work, f"random{seed}.stream")
    made = write_stream(MACHINE, program, path)
    assert made.returncode == 0, made.stderr
    _, positions, _, _ = stream_periods(path)
    rng = random.Random(100 + seed)
    plan = {"next": 0.0}

    def operator(session):
        now = len(session.rows) * PERIOD_S
        if now >= plan["next"] and session.rows and session.rows[-1][12] != FINISHED:
            session.setp("pkmexec.feed-hold", int(rng.random() < 0.3))
            session.setp("pkmexec.feed-override", rng.choice([0.3, 0.7, 1.0, 1.2]))
            plan["next"] = now + rng.uniform(0.1, 0.8)

    with HalSession(MACHINE) as session:
        feeder = session.feed(path)
        table = session.record_until(lambda rows: ended(rows, (FINISHED,)), timeout_s=120, every=operator)
        assert feeder.wait(timeout=30) == 0
    assert_within_limits(table)
    assert [table[f"counts_{j}"][-1] for j in range(6)] == list(positions[-1])


def test_override_100_30_120_keeps_the_limits_and_the_path(work):
    path = streamed(work, "ch5_line.ngc")
    _, positions, ideal, _ = stream_periods(path)

    def operator(session):
        t = len(session.rows) * PERIOD_S
        session.setp("pkmexec.feed-override", 1.0 if t < 0.8 else 0.3 if t < 2.0 else 1.2)

    with HalSession(MACHINE) as session:
        feeder = session.feed(path)
        table = session.record_until(lambda rows: ended(rows, (FINISHED,)), timeout_s=60, every=operator)
        assert feeder.wait(timeout=30) == 0
    assert_within_limits(table)
    assert table["factor"].max() == pytest.approx(1.2)
    assert table["factor"][table["factor"] > 0].min() == pytest.approx(0.3)
    # On the path: each set point lies between the planned ideal values of its nominal period (the drives'
    # space; to the interpolation's own overshoot of a few hundredths of a step).
    rows = released(table)
    tau = table["tau"][rows]
    set_points = np.column_stack([table[f"set_point_{j}"][rows] for j in range(6)]) / 0.001
    nominal = np.vstack([positions[0] * 0 + stream_periods(path)[0], ideal])  # point 0 is the start
    low, high = np.floor(tau).astype(int), np.minimum(np.ceil(tau).astype(int), len(nominal) - 1)
    assert (set_points >= np.minimum(nominal[low], nominal[high]) - 0.05).all()
    assert (set_points <= np.maximum(nominal[low], nominal[high]) + 0.05).all()
    assert [table[f"counts_{j}"][-1] for j in range(6)] == list(positions[-1])


def test_a_stream_beyond_the_range_stops_before_it_naming_the_line(work):
    path = streamed(work, "ch5_line.ngc")
    start, positions, _, lines = stream_periods(path)
    # The stream edited so that drive 1 runs 0.5 mm past its upper stop (900 mm) from period 1500 on: as a
    # stream that did not come from a plan would.
    bad = os.path.join(work, "beyond.stream")
    with open(path) as f, open(bad, "w") as out:
        k = 0
        for text in f:
            fields = text.rstrip("\n").split(",")
            if fields[0] == "p":
                if k >= 1500:
                    fields[2] = repr(900500.0)
                    fields[8] = "900500"
                k += 1
            out.write(",".join(fields) + "\n")
    with HalSession(MACHINE) as session:
        feeder = session.feed(bad)
        table = session.record_until(lambda rows: ended(rows, (STOPPED_AT_LIMIT,)), timeout_s=60)
        feeder.wait(timeout=30)
        session.drain()
    assert table["counts_0"].max() <= 900000
    assert table["tau"].max() < 1500
    assert_within_limits(table)


def test_programs_follow_each_other_without_a_restart_and_one_from_elsewhere_is_refused(work):
    home_to_home = streamed(work, "hexapod_tilt.ngc")
    elsewhere = streamed(work, "ch5_line.ngc")
    with HalSession(MACHINE) as session:
        for _ in range(2):  # the tilt program ends at home: it can run again at once
            count = len(session.rows)
            feeder = session.feed(home_to_home)
            session.record_until(lambda rows: ended(rows, (FINISHED,), after=count) and rows[-1][13] > 0
                                 and len(rows) > count + 100, timeout_s=60)
            assert feeder.wait(timeout=30) == 0
        # ch5_line ends away from home; after it, a program planned from home is refused.
        feeder = session.feed(elsewhere)
        count = len(session.rows)
        session.record_until(lambda rows: len(rows) > count + 100 and ended(rows, (FINISHED,)), timeout_s=60)
        feeder.wait(timeout=30)
        feeder = session.feed(home_to_home)
        count = len(session.rows)
        table = session.record_until(lambda rows: len(rows) > count and ended(rows, (REFUSED,)), timeout_s=30)
        feeder.wait(timeout=30)
    assert table["state"][-1] == REFUSED
