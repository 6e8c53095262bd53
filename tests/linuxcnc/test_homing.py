"""Homing on switches as the textbook describes it (docs/linuxcnc.md): each strut down to its lower boundary switch
at v1, back off it at v2 ≪ v1 until it releases, then to home, with LinuxCNC's own homing and simulated switches
(`pkm linuxcnc config --homing switches`).

The simulated strut is at its home length when LinuxCNC's motor position is 0 (LinuxCNC knows nothing of where it
is before homing): homing is right when LinuxCNC's joint coordinate is the strut's length after it, that is when
each joint's motor offset is minus its home length, to one drive step.
"""
import numpy as np
import pkm

from linuxcnc_run import machine_path, program_path, rtapi_processes, run_linuxcnc

STEP_MM = 0.001  # examples/machines/hexapod_ch5.yaml, drives.step_mm


def test_homing_on_switches_ends_within_one_step_of_home_and_the_program_runs():
    machine_file = machine_path("hexapod_ch5.yaml")
    run = run_linuxcnc(machine_file, program_path("ch5_line.ngc"), config_args=("--homing", "switches"),
                       timeout_s=180)
    assert run.returncode == 0, run.log[-3000:]
    assert run.summary.get("homed"), run.log[-3000:]
    assert run.summary["errors"] == [], run.summary["errors"]
    machine = pkm.Machine.load(machine_file)
    home_lengths = machine.ik(machine.home)
    offsets = np.array(run.summary["motor_offsets"])
    # The origin found on the switches: LinuxCNC's joint = the strut's length, to one step.
    assert np.abs(offsets + home_lengths).max() <= STEP_MM, offsets + home_lengths
    # ... and not by chance: the search went far from where it started (the offset is the whole home length).
    assert np.abs(offsets).min() > 300.0
    assert np.allclose(run.summary["homed_joints"], home_lengths, atol=1e-9)
    assert run.summary["finished"], run.summary
    assert rtapi_processes() == []
