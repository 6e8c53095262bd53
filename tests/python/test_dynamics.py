"""pkm.inverse_dynamics (rigid-body drive forces for many motions) and pkm.plan(..., dynamics=True, elastic=True)
(the elastic machine's response along a run).

Inverse dynamics is checked against the planner's drive forces (the same library at the same poses: the static
part depends on the pose alone) and against physical invariants: at rest the dynamic part vanishes; at zero
acceleration it is quadratic in the speed, and at zero speed linear in the acceleration; the actuator rates are
the Jacobian times the coordinate rates. The elastic run must give the CLI's summary and response.csv.
"""

import csv
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import pkm

SOURCE = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PKM = os.environ.get("PKM_BINARY", "pkm")
MACHINES = SOURCE / "examples" / "machines"
CH5 = str(MACHINES / "hexapod_ch5.yaml")
LINE = str(SOURCE / "examples" / "programs" / "ch5_line.ngc")


@pytest.fixture(scope="module")
def ch5():
    return pkm.Machine.load(CH5)


@pytest.fixture(scope="module")
def planned(ch5):
    return pkm.plan(ch5, LINE, dynamics=True)


def motions(count, seed=7):
    rng = np.random.default_rng(seed)
    poses = np.column_stack([rng.uniform(-40, 40, (count, 2)), rng.uniform(660, 740, count),
                             np.radians(rng.uniform(-8, 8, (count, 3)))])
    velocities = np.column_stack([rng.uniform(-200, 200, (count, 3)), rng.uniform(-0.5, 0.5, (count, 3))])
    accelerations = np.column_stack([rng.uniform(-5e3, 5e3, (count, 3)), rng.uniform(-20, 20, (count, 3))])
    return poses, velocities, accelerations


def test_static_part_is_the_planners(ch5, planned):
    d = planned["dynamics"]
    poses = planned["pose_machine"]
    zero = np.zeros_like(poses)
    result = pkm.inverse_dynamics(ch5, poses, zero, zero)
    assert result["force_N"].shape == d["static_force_N"].shape
    np.testing.assert_allclose(result["static_force_N"], d["static_force_N"], rtol=1e-10, atol=1e-9)
    # At rest nothing but gravity: no dynamic part, the total is the static one, no power.
    assert np.all(result["dynamic_force_N"] == 0.0)
    np.testing.assert_array_equal(result["force_N"], result["static_force_N"])
    assert np.all(result["power_W"] == 0.0)
    # The static part does not depend on the motion.
    _, v, a = motions(len(poses))
    moving = pkm.inverse_dynamics(ch5, poses, v, a)
    np.testing.assert_allclose(moving["static_force_N"], result["static_force_N"], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(moving["force_N"], moving["static_force_N"] + moving["dynamic_force_N"],
                               rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize("rates", ["twist", "coordinates"])
def test_dynamic_part_scales_with_speed_squared_and_acceleration(ch5, rates):
    poses, v, a = motions(300)
    zero = np.zeros_like(poses)
    slow = pkm.inverse_dynamics(ch5, poses, v, zero, rates=rates)["dynamic_force_N"]
    fast = pkm.inverse_dynamics(ch5, poses, 2 * v, zero, rates=rates)["dynamic_force_N"]
    assert np.abs(slow).max() > 1e-3  # the centripetal and Coriolis terms are there
    np.testing.assert_allclose(fast, 4 * slow, rtol=1e-9, atol=1e-9 * np.abs(slow).max())
    once = pkm.inverse_dynamics(ch5, poses, zero, a, rates=rates)["dynamic_force_N"]
    twice = pkm.inverse_dynamics(ch5, poses, zero, 2 * a, rates=rates)["dynamic_force_N"]
    np.testing.assert_allclose(twice, 2 * once, rtol=1e-9, atol=1e-9 * np.abs(once).max())


def test_coordinate_rates_drive_the_actuators_by_the_jacobian(ch5):
    poses, v, _ = motions(50)
    result = pkm.inverse_dynamics(ch5, poses, v, np.zeros_like(v), rates="coordinates")
    expected = np.einsum("nij,nj->ni", ch5.jacobian(poses), v)
    np.testing.assert_allclose(result["actuator_rates_mm_s"], expected, rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(result["power_W"], result["force_N"] * result["actuator_rates_mm_s"] * 1e-3,
                               rtol=1e-12)
    # Translations alone are the same in both forms.
    v[:, 3:] = 0.0
    twist = pkm.inverse_dynamics(ch5, poses, v, np.zeros_like(v))
    coords = pkm.inverse_dynamics(ch5, poses, v, np.zeros_like(v), rates="coordinates")
    np.testing.assert_array_equal(twist["force_N"], coords["force_N"])


def test_single_row_load_and_argument_errors(ch5):
    pose = np.array([0.0, 0.0, 700.0, 0.0, 0.0, 0.0])
    zero = np.zeros(6)
    rest = pkm.inverse_dynamics(ch5, pose, zero, zero)
    assert rest["force_N"].shape == (6,)
    # The drive forces are affine in the external load: each 100 N more adds the same forces.
    loaded = pkm.inverse_dynamics(ch5, pose, zero, zero, load_N_Nmm=[0, 0, 100.0, 0, 0, 0])
    up = pkm.inverse_dynamics(ch5, pose, zero, zero, load_N_Nmm=[0, 0, 200.0, 0, 0, 0])
    np.testing.assert_allclose(up["force_N"] - loaded["force_N"], loaded["force_N"] - rest["force_N"],
                               rtol=1e-9, atol=1e-9)
    with pytest.raises(ValueError, match="same shape"):
        pkm.inverse_dynamics(ch5, np.tile(pose, (3, 1)), np.zeros((2, 6)), np.zeros((3, 6)))
    with pytest.raises(ValueError, match=r"\(N, 6\)"):
        pkm.inverse_dynamics(ch5, np.zeros((3, 5)), np.zeros((3, 5)), np.zeros((3, 5)))
    with pytest.raises(ValueError, match="rates"):
        pkm.inverse_dynamics(ch5, pose, zero, zero, rates="euler")
    far = pose.copy()
    far[2] = 5000.0
    with pytest.raises(pkm.UnreachableError):
        pkm.inverse_dynamics(ch5, np.array([pose, far]), np.zeros((2, 6)), np.zeros((2, 6)))
    assert np.isnan(pkm.inverse_dynamics(ch5, np.array([pose, far]), np.zeros((2, 6)), np.zeros((2, 6)),
                                         errors="nan")["force_N"][1]).all()
    without = pkm.Machine.load(str(MACHINES / "hexaglide.yaml"))
    with pytest.raises(pkm.InputError) as caught:
        pkm.inverse_dynamics(without, pose, zero, zero)
    assert caught.value.key == "dynamics"


def test_elastic_plan_matches_cli(ch5, tmp_path):
    done = subprocess.run([PKM, "plan", LINE, "--machine", CH5, "--dynamics", "--elastic", "--tables", "csv", "--out",
                           tmp_path / "cli", "--json"], capture_output=True, text=True, check=True)
    expected = json.loads(done.stdout)
    expected.pop("planning_time_s")  # a wall-clock time; Python has it as result["planning_time_s"]
    result = pkm.plan(ch5, LINE, dynamics=True, elastic=True)
    assert result["summary"] == expected
    assert "max_dynamic_tool_error_mm" in result["summary"]["dynamics"]
    with open(tmp_path / "cli" / "response.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    e = result["elastic"]
    assert len(e["time_s"]) == len(rows) == expected["ticks"]
    np.testing.assert_array_equal(e["line"], [int(r["line"]) for r in rows])
    np.testing.assert_allclose(e["time_s"], [float(r["time_s"]) for r in rows], atol=1e-6)
    for k, name in enumerate(("dx_mm", "dy_mm", "dz_mm")):
        np.testing.assert_allclose(e["deviation_mm"][:, k], [float(r[name]) for r in rows], rtol=1e-4, atol=1e-12)
    np.testing.assert_allclose(e["tool_error_mm"], np.linalg.norm(e["deviation_mm"], axis=1), rtol=1e-12)
    assert e["tool_error_mm"].max() == expected["dynamics"]["max_dynamic_tool_error_mm"]
    with pytest.raises(ValueError, match="elastic"):
        pkm.plan(ch5, LINE, elastic=True)
