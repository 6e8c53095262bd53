"""A program moves the same in `pkm plan` as on LinuxCNC: at the end of every move, the actuator positions pkm
plans are the joint positions LinuxCNC commanded through pkmkins, to 1e-6 mm (docs/part-programs.md, "What A,
B and C mean"). Both read the program's A B C as G-code's, R = Rz(C)·Ry(B)·Rx(A), whatever convention the
machine file uses: the ch5 and the refined hexapod's is krylov, the others' abc. (Joints of carriages on a
circle, the rotopod's, are degrees: 1e-6 degrees there.)

Between the move ends the two interpolate the orientation differently (LinuxCNC each angle linearly, pkm on
SO(3)), so the comparison is at the ends, where both stop (G61, exact stop): pkm's ticks at the end point,
LinuxCNC's servo periods whose commanded position is the end point.
"""
import csv
import json
import os
import re
import subprocess

import numpy as np
import pkm
import pytest

from linuxcnc_run import PKM, machine_path, program_path, run_linuxcnc

JOINT_TOLERANCE_MM = 1e-6


def move_ends(program):
    """The end points (program coordinates: mm, A B C degrees) of the program's moves, as pkm interprets them."""
    done = subprocess.run([PKM, "interpret", program, "--json"], capture_output=True, text=True, check=True)
    return [np.array(m["end"]) for m in json.loads(done.stdout)["moves"] if m["kind"] in ("rapid", "line")]


def planned(machine, program, out_dir):
    """pkm's plan of the program: the program coordinates and actuator positions (LinuxCNC's units) per tick, in
    full precision from pkm.plan, which plans as `pkm plan` does and writes its files too (out_dir); the CLI's
    actuators.csv holds the same numbers to its six decimals."""
    result = pkm.plan(machine, program, out_dir=out_dir, tables="csv")
    unit = "actuators_mm" if "actuators_mm" in result else "actuators_rad"
    actuators = result[unit] if unit == "actuators_mm" else np.degrees(result[unit])
    printed = np.loadtxt(os.path.join(out_dir, "actuators.csv"), delimiter=",", skiprows=1, ndmin=2)[:, 1:]
    np.testing.assert_allclose(printed, actuators, rtol=0, atol=6e-7)
    with open(os.path.join(out_dir, "path.csv")) as f:
        assert next(csv.reader(f))[3:9] == ["x_program_mm", "y_program_mm", "z_program_mm", "a_abc_deg",
                                            "b_abc_deg", "c_abc_deg"]
    return np.column_stack([result["xyz_program_mm"], result["abc_deg"]]), actuators


def program_origin(run):
    """G54 of the generated configuration: the machine file's program origin (X Y Z it sets)."""
    with open(os.path.join(run.config_dir, "machine.ini")) as f:
        startup = re.search(r"^RS274NGC_STARTUP_CODE = .*G10 L2 P1(.*)$", f.read(), re.M).group(1)
    origin = np.zeros(6)
    for letter, value in re.findall(r"([XYZ])(\S+)", startup):
        origin["XYZ".index(letter)] = float(value)
    return origin


def joints_at_move_ends(machine_file, program, tmp_path):
    """(pkm's actuators, LinuxCNC's joints) at every move end, in LinuxCNC's units (mm, or deg)."""
    machine = pkm.Machine.load(machine_file)
    controlled = np.array(machine.controlled_axes)
    path, actuators = planned(machine, program, str(tmp_path / "plan"))
    run = run_linuxcnc(machine_file, program)
    assert run.returncode == 0 and run.summary.get("finished"), run.log[-3000:]
    assert run.summary["errors"] == [], run.summary["errors"]
    origin = program_origin(run)
    axes, joints = run.axes(), run.joints()
    ends = move_ends(program)
    assert len(ends) >= 3
    pairs = []
    for end in ends:
        # pkm: the ticks at the end point, where the tool stops (exact stop). The ticks just before and after are
        # within 1e-6 mm of it, but their struts are not: only the tick at the end is compared.
        distance = np.abs(path - end)[:, controlled].max(axis=1)
        ours = distance < 1e-9
        # LinuxCNC: the periods whose commanded position is the end point, machine coordinates = program + G54.
        theirs = np.abs(axes - (end + origin))[:, controlled].max(axis=1) < 1e-9
        assert ours.any() and theirs.any(), f"move end {end} not reached by both"
        pairs.append((actuators[ours], joints[theirs]))
    return pairs


def assert_same_joints(pairs):
    worst = 0.0
    for ours, theirs in pairs:
        # Every tick at rest at the end against every LinuxCNC period there.
        worst = max(worst, np.abs(ours[:, None, :] - theirs[None, :, :]).max())
    print(f"largest joint difference at the move ends: {worst:.3g} (mm, or deg for carriages on a circle)")
    assert worst <= JOINT_TOLERANCE_MM, worst


@pytest.mark.parametrize("machine_file, program", [("hexapod_ch5.yaml", "hexapod_tilt.ngc"),
                                                   ("hexapod_refined.yaml", "hexapod_tilt.ngc"),
                                                   ("hexapod_genhexkins.yaml", "hexapod_tilt.ngc"),
                                                   ("hexaglide.yaml", "hexapod_tilt.ngc"),
                                                   ("rotopod.yaml", "hexapod_tilt.ngc"),
                                                   ("tripod.yaml", "tripod_tilt.ngc")])
def test_shipped_five_axis_programs_end_every_move_on_the_same_joints(machine_file, program, tmp_path):
    assert_same_joints(joints_at_move_ends(machine_path(machine_file), program_path(program), tmp_path))


def generated_program(seed, moves=8):
    """Random five-axis moves around program zero, exact stop at every corner, rapid and feed."""
    rng = np.random.default_rng(seed)
    lines = ["G21 G90 G17 G94 G61", "G0 X0 Y0 Z0 A0 B0 C0"]
    for k in range(moves):
        x, y, z = rng.uniform(-25, 25, 3)
        a, b, c = rng.uniform(-7, 7, 3)
        word = "G0" if k % 4 == 3 else "G1"
        feed = "" if word == "G0" else f" F{rng.uniform(600, 2400):.0f}"
        lines.append(f"{word} X{x:.4f} Y{y:.4f} Z{z:.4f} A{a:.4f} B{b:.4f} C{c:.4f}{feed}")
    lines += ["G0 X0 Y0 Z0 A0 B0 C0", "M2"]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("machine_file, seed", [("hexapod_ch5.yaml", 11), ("hexapod_ch5.yaml", 12),
                                                ("hexapod_genhexkins.yaml", 13)])
def test_generated_five_axis_moves_end_on_the_same_joints(machine_file, seed, tmp_path):
    os.chmod(tmp_path, 0o755)  # rtapi_app reads the program as another user (linuxcnc_run.py)
    program = tmp_path / f"five_axis_{seed}.ngc"
    program.write_text(generated_program(seed))
    os.chmod(program, 0o644)
    assert_same_joints(joints_at_move_ends(machine_path(machine_file), str(program), tmp_path))
