"""LinuxCNC runs the shipped machines headless through pkm's kinematics module (docs/linuxcnc.md).

Every sample is one servo period of LinuxCNC's motion controller: the Cartesian position it commanded and the
joint positions its kinematics module returned for it in that period. pkm's own inverse kinematics (the Python
module, an independent path into the library) must give the same joints. LinuxCNC's A B C are G-code's,
R = Rz(C)·Ry(B)·Rx(A), whatever the machine file's convention (docs/part-programs.md, "What A, B and C mean"):
Machine.pose_from_abc turns them into the machine's own poses for Machine.ik.
"""
import json
import os
import re

import numpy as np
import pkm
import pytest

from linuxcnc_run import machine_path, program_path, rtapi_processes, run_linuxcnc

RESULTS = os.environ.get("PKM_LINUXCNC_RESULTS")  # where the thread-time comparison is written (make bench)


def machine_poses(machine, axes):
    """LinuxCNC's positions (mm; A B C in degrees, G-code's) as the machine's own poses (mm, rad)."""
    poses = axes.copy()
    poses[:, 3:] = np.radians(poses[:, 3:])
    return machine.pose_from_abc(poses)


def abc_degrees(machine, pose):
    """A machine pose (mm, rad, the machine's convention) as LinuxCNC's position (mm; A B C degrees)."""
    position = machine.abc_from_pose(pose)
    position[3:] = np.degrees(position[3:])
    return position


def coordinated(run):
    rows = run.column("coordinated") > 0.5
    assert rows.sum() > 500, "too few samples of coordinated motion"
    return rows


def joint_error_against_pkm(run, machine):
    rows = coordinated(run)
    joints = run.joints()[rows]
    expected = machine.ik(machine_poses(machine, run.axes()[rows]), check_limits=False)
    if machine.actuator_unit == "rad":
        expected = np.degrees(expected)
    return np.abs(joints - expected).max()


def assert_clean(run):
    assert run.returncode == 0, run.log[-3000:]
    assert run.summary, run.log[-3000:]
    assert run.summary["errors"] == [], run.summary["errors"]
    assert run.summary["homed"] and run.summary["finished"]
    assert run.summary["overruns"] == 0
    assert rtapi_processes() == [], "LinuxCNC left its real-time process behind"


def assert_fk_matches(run, machine):
    """LinuxCNC's Cartesian position after homing and at the end came from the module's forward kinematics."""
    for joints_key, position_key in (("homed_joints", "homed_position"), ("final_joints", "final_position")):
        joints = np.array(run.summary[joints_key])
        if machine.actuator_unit == "rad":
            joints = np.radians(joints)
        position = np.array(run.summary[position_key])
        solved = abc_degrees(machine, machine.fk(joints[None, :], machine.home)[0])
        controlled = np.array(machine.controlled_axes)
        assert np.abs(solved - position)[controlled].max() < 1e-8, (joints_key, solved, position)


def thread_clocks(run):
    clocks = run.column("motion_controller_clocks")[coordinated(run)]
    return {"median": float(np.median(clocks)), "mean": float(clocks.mean()),
            "p99_9": float(np.percentile(clocks, 99.9)), "max": float(clocks.max())}


def run_through_pkmkins(machine_file, program):
    """Runs `program` on the machine through pkmkins and checks every period against pkm's own IK and FK."""
    machine = pkm.Machine.load(machine_path(machine_file))
    run = run_linuxcnc(machine_path(machine_file), program_path(program))
    assert_clean(run)
    assert joint_error_against_pkm(run, machine) <= 1e-9
    assert_fk_matches(run, machine)
    return machine, run


def test_ch5_hexapod_runs_a_five_axis_program_through_pkmkins():
    machine, run = run_through_pkmkins("hexapod_ch5.yaml", "hexapod_tilt.ngc")
    # The program was run: its extreme points (program zero is the home point X0 Y0 Z700) were commanded.
    axes = run.axes()[coordinated(run)]
    assert axes[:, 0].max() == pytest.approx(20.0, abs=1e-6) and axes[:, 0].min() == pytest.approx(-15.0, abs=1e-6)
    assert axes[:, 2].max() == pytest.approx(705.0, abs=1e-6) and axes[:, 2].min() == pytest.approx(695.0, abs=1e-6)
    assert axes[:, 5].max() == pytest.approx(8.0, abs=1e-6) and axes[:, 5].min() == pytest.approx(-6.0, abs=1e-6)
    # The homed pose is the machine file's home, through the module's forward kinematics.
    home = abc_degrees(machine, machine.home)
    assert np.abs(np.array(run.summary["homed_position"]) - home).max() < 1e-8


def test_genhexkins_and_pkmkins_agree_on_the_same_geometry():
    name = "hexapod_genhexkins.yaml"
    machine = pkm.Machine.load(machine_path(name))
    ours = run_linuxcnc(machine_path(name), program_path("hexapod_tilt.ngc"))
    theirs = run_linuxcnc(machine_path(name), program_path("hexapod_tilt.ngc"), kinematics="genhexkins")
    assert_clean(ours)
    assert_clean(theirs)
    assert ours.summary["kinematics"] == "pkmkins" and theirs.summary["kinematics"] == "genhexkins"
    assert joint_error_against_pkm(ours, machine) <= 1e-9
    assert joint_error_against_pkm(theirs, machine) <= 1e-6
    assert_fk_matches(ours, machine)
    # Both ran the same program to the same end.
    assert np.abs(np.array(ours.summary["final_position"]) - theirs.summary["final_position"]).max() < 1e-6
    # The servo thread's time, from LinuxCNC's own pin motion-controller.time (CPU clocks per period), against the
    # same program with no kinematics at all (trivkins: joints = coordinates): what is left is the kinematics'.
    baseline = run_linuxcnc(machine_path(name), program_path("hexapod_tilt.ngc"), kinematics="trivkins")
    assert_clean(baseline)
    clocks = {"pkmkins": thread_clocks(ours), "genhexkins": thread_clocks(theirs), "trivkins": thread_clocks(baseline)}
    # Medians: a period the scheduler interrupts costs milliseconds and would dominate a mean.
    kinematics = {k: clocks[k]["median"] - clocks["trivkins"]["median"] for k in ("pkmkins", "genhexkins")}
    comparison = {"program": "examples/programs/hexapod_tilt.ngc", "machine": f"examples/machines/{name}",
                  "motion_controller_clocks": clocks, "kinematics_clocks_median": kinematics,
                  "kinematics_ratio_pkmkins_to_genhexkins": kinematics["pkmkins"] / kinematics["genhexkins"]}
    print(json.dumps(comparison, indent=2))
    if RESULTS:
        with open(RESULTS, "w") as f:
            json.dump(comparison, f, indent=2)


def test_tripod_runs_with_its_three_coordinates():
    _, run = run_through_pkmkins("tripod.yaml", "tripod_tilt.ngc")
    with open(os.path.join(run.config_dir, "machine.ini")) as f:
        assert re.search(r"^COORDINATES = Z A B$", f.read(), re.M)
    assert run.summary["joints"] == 3
    axes = run.axes()[coordinated(run)]
    assert axes[:, 3].max() == pytest.approx(4.0, abs=1e-6) and axes[:, 4].min() == pytest.approx(-4.0, abs=1e-6)


def test_hexaglide_runs_with_carriages_as_joints():
    _, run = run_through_pkmkins("hexaglide.yaml", "hexapod_tilt.ngc")
    assert run.summary["joints"] == 6


def test_a_program_leaving_the_workspace_stops_with_a_limit_error(tmp_path):
    program = tmp_path / "too_high.ngc"
    program.write_text("G21 G90 G94\nG0 X0 Y0 Z0\nG1 Z400 F3000\nM2\n")
    os.chmod(tmp_path, 0o755)
    os.chmod(program, 0o644)
    run = run_linuxcnc(machine_path("hexapod_ch5.yaml"), str(program))
    assert run.returncode == 0, run.log[-3000:]
    assert not run.summary["finished"]
    assert any(re.search(r"limit|kinematics", e, re.I) for e in run.summary["errors"]), run.summary["errors"]
    # No joint was commanded past the machine's 900 mm struts.
    assert run.joints("command").max() <= 900.0 + 1e-9
    assert rtapi_processes() == []


def test_a_machine_with_an_unreachable_home_is_refused_when_the_module_loads():
    def move_home_out_of_reach(config_dir):
        path = os.path.join(config_dir, "machine.yaml")
        with open(path) as f:
            text = f.read()
        with open(path, "w") as f:
            f.write(text.replace("home: [0, 0, 700, 0, 0, 0]", "home: [0, 0, 1500, 0, 0, 0]"))

    run = run_linuxcnc(machine_path("hexapod_ch5.yaml"), program_path("hexapod_tilt.ngc"),
                       edit_config=move_home_out_of_reach, timeout_s=60)
    # The module's own message, with the machine file's line, column and key, then LinuxCNC's refusal.
    assert re.search(r"pkmkins: .*machine\.yaml:\d+:\d+: home: .*actuator_max 900 mm", run.log), run.log[-3000:]
    assert "insmod for pkmkins failed" in run.log
    assert run.returncode != 0
    assert not run.summary.get("finished", False)
    assert rtapi_processes() == []


@pytest.mark.parametrize("machine_file, program", [("rotopod.yaml", "hexapod_tilt.ngc"),
                                                   ("tricept.yaml", "ch5_line.ngc")])
def test_carriages_on_a_circle_and_a_tricept_run_too(machine_file, program):
    """Angular joints (the rotopod's carriages, in degrees), and the tricept's X Y Z with its passive leg."""
    machine, run = run_through_pkmkins(machine_file, program)
    assert run.summary["joints"] == machine.actuator_count
