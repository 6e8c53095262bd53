"""Batch kinematics of pkm.Machine: the same numbers as the CLI (pkm ik / fk / jacobian) on every shipped machine,
round trips, and batches equal to single calls bit for bit on any number of threads."""

from __future__ import annotations

import numpy as np
import pytest

import pkm
from kinematics_helpers import (HEXAPOD_CH5, MACHINE_FILES, assert_close, cli_json, deg_from_rad, pose_from_user,
                                poses_near_home, rad_from_deg, user_indices, user_poses_near_home, user_text)

MACHINE_IDS = [f.stem for f in MACHINE_FILES]


@pytest.fixture(scope="module", params=MACHINE_FILES, ids=MACHINE_IDS)
def machine_file(request):
    return request.param


@pytest.fixture(scope="module")
def machine(machine_file):
    return pkm.Machine.load(machine_file)


def actuators_from_cli(machine: pkm.Machine, values) -> np.ndarray:
    values = np.asarray(values, dtype=float)
    return np.array([rad_from_deg(v) for v in values]) if machine.actuator_unit == "rad" else values


def user_actuators(machine: pkm.Machine, q) -> np.ndarray:
    return np.array([deg_from_rad(v) for v in q]) if machine.actuator_unit == "rad" else np.asarray(q)


def test_ik_equals_cli(machine_file, machine):
    for pose_user in user_poses_near_home(machine, 3, seed=1):
        shown = pose_user[user_indices(machine)]
        expected = cli_json("ik", "--machine", str(machine_file), "--pose", user_text(shown))
        q = machine.ik(pose_from_user(pose_user))
        assert_close(q, actuators_from_cli(machine, expected["actuators"]), what=f"ik {pose_user}")


def test_fk_equals_cli(machine_file, machine):
    user = user_poses_near_home(machine, 3, seed=2)
    guess_user = user[0]
    for pose_user in user[1:]:
        q_user = user_actuators(machine, machine.ik(pose_from_user(pose_user)))
        q = actuators_from_cli(machine, q_user)  # the doubles the CLI reads from q_user's text
        expected = cli_json("fk", "--machine", str(machine_file), "--actuators", user_text(q_user), "--guess",
                            user_text(guess_user[user_indices(machine)]))
        pose = machine.fk(q, pose_from_user(guess_user), warm=False)
        shown = [v if i < 3 else deg_from_rad(v) for i, v in enumerate(pose)]
        assert_close(np.array(shown)[user_indices(machine)], expected["pose"], what=f"fk {q_user}")
        _, info = machine.fk(q, pose_from_user(guess_user), warm=False, info=True)
        assert info["branch"] == expected["branch"]
        assert info["iterations"] == expected["iterations"]


def test_fk_all_equals_cli(machine_file, machine):
    q = machine.ik(machine.home)
    q_user = user_actuators(machine, q)
    result = cli_json("fk", "--machine", str(machine_file), "--actuators", user_text(q_user), "--all") \
        if _enumerates(machine, q) else None
    if result is None:
        with pytest.raises(pkm.UnsupportedError):
            machine.fk_all(q)
        return
    solutions = machine.fk_all(actuators_from_cli(machine, q_user))
    assert len(solutions) == len(result["solutions"]) >= 1
    for mine, cli in zip(solutions, result["solutions"]):
        shown = [v if i < 3 else deg_from_rad(v) for i, v in enumerate(mine["pose"])]
        assert_close(np.array(shown)[user_indices(machine)], cli["pose"], rel=1e-12, what="fk_all pose")
        assert mine["branch"] == cli["branch"]


def _enumerates(machine: pkm.Machine, q) -> bool:
    try:
        machine.fk_all(q)
        return True
    except pkm.UnsupportedError:
        return False


def test_jacobian_and_conditioning_equal_cli(machine_file, machine):
    pose_user = user_poses_near_home(machine, 2, seed=3)[1]
    expected = cli_json("jacobian", "--machine", str(machine_file), "--pose",
                        user_text(pose_user[user_indices(machine)]))
    pose = pose_from_user(pose_user)
    assert_close(machine.jacobian(pose), expected["jacobian"], what="jacobian")
    assert machine.controlled_names == expected["columns"]
    measures = machine.conditioning(pose)
    assert_close(measures["det"], expected["determinant"], what="det")
    assert_close(measures["condition_number"], expected["condition_number"], what="condition number")
    assert_close(measures["delta_rho"], expected["error_amplification"], what="delta rho")
    assert measures["delta_rho"] == pytest.approx(np.hypot.reduce([measures[k] for k in ("s_x", "s_y", "s_z")]))


def test_ik_fk_round_trip(machine):
    poses = poses_near_home(machine, 20, seed=4, range_mm=10.0, range_deg=3.0)
    q = machine.ik(poses)
    back = machine.fk(q, warm=False)
    controlled = np.array(machine.controlled_axes)
    # The solver stops at 1e-10 in the actuators (mm, or rad: ~1e-8 mm at a rotopod's radius).
    np.testing.assert_allclose(back[:, controlled], poses[:, controlled], rtol=0, atol=1e-7)
    np.testing.assert_allclose(machine.ik(back), q, rtol=0, atol=1e-9)
    # Each row from the previous row's solution: the same poses.
    warm = machine.fk(q, poses[0])
    np.testing.assert_allclose(warm[:, controlled], poses[:, controlled], rtol=0, atol=1e-7)


def test_single_pose_shapes(machine):
    pose = machine.home
    n, m = machine.actuator_count, sum(machine.controlled_axes)
    assert machine.ik(pose).shape == (n,)
    assert machine.ik(pose[None, :]).shape == (1, n)
    assert machine.ik(np.empty((0, 6))).shape == (0, n)
    assert machine.fk(machine.ik(pose)).shape == (6,)
    assert machine.jacobian(pose).shape == (n, m)
    assert machine.jacobian(pose[None, :]).shape == (1, n, m)
    assert isinstance(machine.conditioning(pose)["delta_rho"], float)


@pytest.fixture(scope="module")
def hexapod():
    return pkm.Machine.load(HEXAPOD_CH5)


@pytest.fixture(scope="module")
def hexapod_poses(hexapod):
    # More rows than one TBB block, so that the batch runs in parallel.
    rng = np.random.default_rng(5)
    poses = hexapod.home + rng.uniform(-1, 1, (5000, 6)) * np.array([40, 40, 40, 0.1, 0.1, 0.1])
    return poses


def test_batch_equals_single_calls_bit_for_bit(hexapod, hexapod_poses):
    poses = hexapod_poses
    q = hexapod.ik(poses)
    assert np.array_equal(q, np.array([hexapod.ik(p) for p in poses]))
    sample = slice(0, 5000, 7)  # single calls of every kind, on a sample of the rows
    j = hexapod.jacobian(poses)
    assert np.array_equal(j[sample], np.array([hexapod.jacobian(p) for p in poses[sample]]))
    c = hexapod.conditioning(poses)
    for key, column in c.items():
        assert np.array_equal(column[sample], np.array([hexapod.conditioning(p)[key] for p in poses[sample]])), key
    cold = hexapod.fk(q, warm=False)
    assert np.array_equal(cold[sample], np.array([hexapod.fk(row, warm=False) for row in q[sample]]))


def test_results_do_not_depend_on_thread_count(hexapod, hexapod_poses):
    default_threads = pkm.get_threads()
    results = {}
    try:
        for threads in (1, 2, 3):
            pkm.set_threads(threads)
            assert pkm.get_threads() == threads
            q = hexapod.ik(hexapod_poses)
            results[threads] = (q, hexapod.fk(q, warm=False), hexapod.jacobian(hexapod_poses),
                                hexapod.conditioning(hexapod_poses)["delta_rho"])
    finally:
        pkm.set_threads(None)
    assert pkm.get_threads() == default_threads
    for threads in (2, 3):
        for a, b in zip(results[1], results[threads]):
            assert np.array_equal(a, b, equal_nan=True)


def test_errors_nan_marks_only_the_failing_rows(hexapod, hexapod_poses):
    poses = hexapod_poses[:2000].copy()
    poses[[3, 1500], 2] = 5000.0  # far above the struts' reach
    q = hexapod.ik(poses, errors="nan")
    assert np.isnan(q[[3, 1500]]).all()
    good = np.setdiff1d(np.arange(2000), [3, 1500])
    assert np.array_equal(q[good], hexapod.ik(poses[good]))
    with pytest.raises(pkm.UnreachableError) as raised:
        hexapod.ik(poses)
    assert raised.value.row == 3 and "poses[3]" in str(raised.value)
    # Without the range check the far pose has strut lengths (beyond actuator_max).
    unchecked = hexapod.ik(poses[3], check_limits=False)
    assert np.all(unchecked > hexapod.actuator_limits["max"])


def test_warm_fk_on_scattered_rows_equals_cold(hexapod, hexapod_poses):
    q = hexapod.ik(hexapod_poses[:1000])  # rows up to 80 mm and 0.2 rad apart: no path
    np.testing.assert_allclose(hexapod.fk(q), hexapod_poses[:1000], rtol=0, atol=1e-8)


def test_warm_fk_along_a_path_with_and_without_extrapolation(hexapod):
    s = np.linspace(0, 2 * np.pi, 4000)  # 0.06 mm steps round a 40 mm circle, turning slowly
    path = hexapod.home + np.c_[40 * np.sin(s), 40 * (1 - np.cos(s)), 10 * np.sin(0.3 * s), 0.05 * np.sin(s),
                                0.05 * np.cos(s) - 0.05, 0 * s]
    q = hexapod.ik(path)
    plain, plain_info = hexapod.fk(q, info=True)
    extrapolated, extrapolated_info = hexapod.fk(q, extrapolate=True, info=True)
    np.testing.assert_allclose(plain, path, rtol=0, atol=1e-8)
    np.testing.assert_allclose(extrapolated, path, rtol=0, atol=1e-8)
    # The servo loop's extrapolated start needs fewer iterations on a smooth path.
    assert extrapolated_info["iterations"].mean() < plain_info["iterations"].mean()


def test_fk_errors_nan_and_restart_after_a_failed_row(hexapod, hexapod_poses):
    q = hexapod.ik(hexapod_poses[:50])
    q[10] = 100.0  # below actuator_min: refused
    for warm in (True, False):
        poses = hexapod.fk(q, errors="nan", warm=warm)
        assert np.isnan(poses[10]).all()
        others = np.delete(np.arange(50), 10)
        np.testing.assert_allclose(poses[others], hexapod_poses[others], rtol=0, atol=1e-8)
        with pytest.raises(pkm.LimitExceededError) as raised:
            hexapod.fk(q, warm=warm)
        assert raised.value.row == 10 and "actuator_min" in str(raised.value)
    poses, info = hexapod.fk(q, errors="nan", info=True)
    assert info["iterations"][10] == -1 and np.isnan(info["residual_mm"][10]) and info["branch"][10] == -1
    assert (info["branch"][:10] == 0).all() and (info["residual_mm"][:10] <= 1e-10).all()


def test_conditioning_nan_where_unreachable(hexapod):
    poses = np.array([hexapod.home, hexapod.home + [0, 0, 5000, 0, 0, 0]])
    c = hexapod.conditioning(poses)
    assert np.isfinite(c["delta_rho"][0]) and np.isnan(c["delta_rho"][1])
    with pytest.raises(pkm.UnreachableError):
        hexapod.conditioning(poses, errors="raise")
