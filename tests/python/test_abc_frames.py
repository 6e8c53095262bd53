"""The frames of poses in Python: a program's A B C are G-code's (R = Rz(C)·Ry(B)·Rx(A)) on every machine, and
Machine.pose_from_abc / abc_from_pose convert them to and from the machine's own convention, which ik and fk take.
pkm.plan gives both frames under names that say which (docs/python.md, "Conventions").
"""
import os
from pathlib import Path

import numpy as np
import pytest

import pkm

SOURCE = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
MACHINES = SOURCE / "examples" / "machines"
PROGRAMS = SOURCE / "examples" / "programs"


def rotation_abc(a, b, c):
    """Rz(C)·Ry(B)·Rx(A), written out here apart from the library."""
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    rx = np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
    ry = np.array([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])
    rz = np.array([[cc, -sc, 0], [sc, cc, 0], [0, 0, 1]])
    return rz @ ry @ rx


def rotation_krylov(psi, theta, gamma):
    """Rz(−ψ)·Rx(−ϑ)·Ry(−γ), the ch5 hexapod's convention (docs/machine-file.md)."""
    return rotation_abc(0, 0, -psi) @ rotation_abc(-theta, 0, 0) @ rotation_abc(0, -gamma, 0)


@pytest.fixture(scope="module")
def ch5():
    return pkm.Machine.load(str(MACHINES / "hexapod_ch5.yaml"))


def test_pose_from_abc_is_the_same_rotation_in_krylov(ch5):
    assert ch5.angle_convention == "krylov"
    rng = np.random.default_rng(5)
    abc = np.column_stack([rng.uniform(-30, 30, (50, 3)), np.radians(rng.uniform(-15, 15, (50, 3)))])
    krylov = ch5.pose_from_abc(abc)
    assert krylov.shape == (50, 6)
    np.testing.assert_array_equal(krylov[:, :3], abc[:, :3])
    for given, converted in zip(abc, krylov):
        np.testing.assert_allclose(rotation_krylov(*converted[3:]), rotation_abc(*given[3:]), atol=1e-14)
    np.testing.assert_allclose(ch5.abc_from_pose(krylov), abc, atol=1e-13)
    assert ch5.pose_from_abc(abc[0]).shape == (6,)
    with pytest.raises(ValueError):
        ch5.pose_from_abc(np.zeros((2, 5)))


def test_a_tilt_about_x_is_a_not_the_machines_first_angle(ch5):
    """X20 Y-10 Z-5 A4 of hexapod_tilt.ngc: A is a tilt about X, not the krylov yaw ψ."""
    program = np.array([20.0, -10.0, 695.0, np.radians(4.0), 0.0, 0.0])
    as_abc = ch5.ik(ch5.pose_from_abc(program))
    as_krylov = ch5.ik(program)
    assert np.abs(as_abc - as_krylov).max() > 10.0


def test_plan_names_its_frames(ch5):
    result = pkm.plan(ch5, str(PROGRAMS / "hexapod_tilt.ngc"))
    assert "pose" not in result
    machine_pose, xyz, abc = result["pose_machine"], result["xyz_program_mm"], result["abc_deg"]
    # Program zero of the ch5 hexapod is the home tool point at z = 700 mm (motion.program_origin_mm).
    base = np.column_stack([xyz + [0.0, 0.0, 700.0], np.radians(abc)])
    np.testing.assert_allclose(ch5.pose_from_abc(base), machine_pose, atol=1e-9)
    np.testing.assert_allclose(ch5.ik(machine_pose), result["actuators_mm"], atol=1e-9)
    # The ends of the first two moves (A4, then B-5 C8) as the program writes them, in abc_deg; between the
    # ends the rotation goes the shortest way (slerp), not each angle linearly.
    for end in ([20, -10, -5, 4, 0, 0], [-15, 10, -5, 4, -5, 8]):
        assert np.abs(np.column_stack([xyz, abc]) - end).max(axis=1).min() < 1e-9, end
