"""LinuxCNC proper with pkm's executor: `pkm linuxcnc config --execute` (docs/linuxcnc.md).

LinuxCNC runs headless on the generated configuration (linuxcnc/headless_run.py): it homes the machine, then
runs a sequence of pkm execution streams (fed to pkmexec by linuxcnc/pkm_feed.py --machine-on) and G-code
programs (run by LinuxCNC itself), recording every servo period. The drives must get pkm's steps period by
period while pkmexec has them, LinuxCNC's motion must be disabled meanwhile and take the drives back where
pkmexec left them, nothing may jump at a hand-over, and a program must be refused while LinuxCNC has not
handed the drives over.
"""
import os
import shutil
import tempfile

import numpy as np
import pytest

from hal_session import stream_periods, write_stream
from linuxcnc_run import machine_path, program_path, rtapi_processes, run_linuxcnc

MACHINE = machine_path("hexapod_ch5.yaml")
STEP_MM, PERIOD_S = 0.001, 1e-3
SPEED_MM_S = 100.0  # examples/machines/hexapod_ch5.yaml, limits.actuator_speed
RUNNING, STARVED = 1, 2


@pytest.fixture
def work():
    directory = tempfile.mkdtemp(prefix="pkm-execute-test-", dir="/tmp")
    os.chmod(directory, 0o755)
    yield directory
    shutil.rmtree(directory, ignore_errors=True)


def stream_file(work, program):
    path = os.path.join(work, os.path.basename(program) + ".stream")
    made = write_stream(MACHINE, program_path(program), path)
    assert made.returncode == 0, made.stderr
    os.chmod(path, 0o644)
    return path


def back_home(work):
    """A G-code program that takes the machine back to its home pose (base frame)."""
    path = os.path.join(work, "back_home.ngc")
    with open(path, "w") as f:
        f.write("G21 G90\nG53 G1 X0 Y0 Z700 A0 B0 C0 F3000\nM2\n")
    os.chmod(path, 0o644)
    return path


def columns(run, prefix, suffix=""):
    return np.column_stack([run.column(f"{prefix}_{j}{suffix}") for j in range(6)])


def executions(run):
    """(first, last) row of every stretch of periods in which pkmexec had the drives: it releases the program's
    last period in row `last`, and its state says finished there."""
    active = np.isin(run.column("pkmexec_state"), (RUNNING, STARVED)).astype(int)
    edges = np.diff(np.concatenate([[0], active, [0]]))
    return list(zip(np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0]))


def without_rest(positions):
    """The positions from the first period that leaves the start to the last that arrives at the end."""
    moving = np.nonzero(np.any(positions != positions[0], axis=1))[0]
    arriving = np.nonzero(np.any(positions != positions[-1], axis=1))[0]
    return positions[moving[0]:arriving[-1] + 2]


def assert_no_jump(run, offsets):
    """The drives never move faster than their speed limit, hand-overs included (one step of slack)."""
    drives = columns(run, "drive", "_position") - offsets
    speed = np.abs(np.diff(drives, axis=0)) / PERIOD_S
    assert speed.max() <= SPEED_MM_S + STEP_MM / PERIOD_S, speed.max()


def test_linuxcnc_hands_the_drives_to_pkm_and_takes_them_back(work):
    line = stream_file(work, "ch5_line.ngc")
    _, planned, _, planned_lines = stream_periods(line)
    sequence = ["machine-off", line, "machine-on", line, back_home(work), line]
    run = run_linuxcnc(MACHINE, ":".join(sequence), config_args=("--execute",), timeout_s=150)
    assert run.returncode == 0, run.log[-3000:]
    summary = run.summary
    assert summary["errors"] == [], summary["errors"]
    programs = summary["programs"]
    # With LinuxCNC's machine off the drives are not handed over: refused before anything moved.
    assert programs[1]["exit"] == 1 and "not handed over" in programs[1]["said"], programs[1]
    assert programs[3]["exit"] == 0 and programs[5]["exit"] == 0, programs
    assert programs[4]["state_on"], programs[4]
    assert summary["handovers"] == 2 and summary["finished"] is False  # the refused stream is not a success

    offsets = np.array(summary["motor_offsets"])
    counts = columns(run, "pkmexec", "_counts")
    drives = columns(run, "drive", "_position")
    enabled = run.column("motion_enabled").astype(bool)
    stretches = executions(run)
    assert len(stretches) == 2, stretches
    for first, last in stretches:
        # pkm's steps, period by period, every one once and in order, with their program lines.
        executed = counts[first:last + 1]
        assert np.array_equal(without_rest(executed), without_rest(planned))
        assert executed[-1].tolist() == planned[-1].tolist()
        moving = np.nonzero(np.any(executed != executed[0], axis=1))[0][0]
        lines = run.column("pkmexec_line")[first + moving:last + 1]
        assert set(lines) <= set(planned_lines) and lines[-1] == planned_lines[-1]
        # The drives are where pkmexec puts them (LinuxCNC's motor offset from homing added)...
        assert np.abs(drives[first:last + 1] - (executed * STEP_MM + offsets)).max() <= 1e-9
        # ... and LinuxCNC's motion is off meanwhile (one period after pkmexec takes them).
        assert not enabled[first + 2:last].any()
    # Between the two executions LinuxCNC had the drives again, from where pkm left them, and brought them home;
    # it was on when it handed them over the second time.
    between = slice(stretches[0][1], stretches[1][0])
    assert enabled[between].any() and enabled[stretches[1][0] - 5:stretches[1][0]].all()
    assert np.abs(np.diff(drives[between], axis=0)).max() > 0.01  # LinuxCNC moved them (G-code back home)
    assert_no_jump(run, offsets)
    # LinuxCNC's own view of the joints at the end is pkm's last position; its forward kinematics followed.
    assert np.allclose(summary["final_joints"], planned[-1] * STEP_MM, atol=1e-9)
    assert summary["final_position"][0] == pytest.approx(50.0, abs=1e-3)
    assert summary["pkmkins_fk_failures"] == summary["pkmkins_fk_failures_homed"]
    assert rtapi_processes() == []


def test_servo_drives_homed_on_switches_follow_pkms_steps_under_hold_and_override(work):
    line = stream_file(work, "ch5_line.ngc")
    _, planned, _, _ = stream_periods(line)
    operator = "0.4:hold=1,1.0:hold=0,1.3:override=0.3,2.2:override=1.2"
    run = run_linuxcnc(MACHINE, line, config_args=("--execute", "--drives", "servo", "--homing", "switches"),
                       timeout_s=150, operator=operator)
    assert run.returncode == 0, run.log[-3000:]
    summary = run.summary
    assert summary["errors"] == [] and summary["finished"], summary
    offsets = np.array(summary["motor_offsets"])
    assert np.abs(offsets).min() > 300.0  # homed on the switches: the motors' zero is far from the struts' zero
    counts = columns(run, "pkmexec", "_counts")
    drives = columns(run, "drive", "_position") - offsets
    (first, last), = executions(run)
    # Held and overridden, the program still ends exactly where it was planned to.
    assert counts[last].tolist() == planned[-1].tolist()
    assert len(counts[first:last]) > len(planned) + 500  # it was slowed down: it took longer than planned
    # The servo loops follow pkmexec's commands closely and settle on the last one within a step.
    following = np.abs(drives[first:last] - counts[first:last] * STEP_MM)
    assert following.max() < 0.05, following.max()
    assert np.abs(drives[-1] - planned[-1] * STEP_MM).max() <= STEP_MM
    speed = np.abs(np.diff(counts[first:last], axis=0)) * STEP_MM / PERIOD_S
    assert speed.max() <= SPEED_MM_S + STEP_MM / PERIOD_S
    assert rtapi_processes() == []
