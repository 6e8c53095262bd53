"""pkm.modes, pkm.compliance and pkm.workspace against the CLI (`pkm modes`, `pkm compliance`, `pkm workspace`).

Poses go to Python in radians and to the CLI in degrees; the results must agree to 1e-12 (relative) where the
CLI prints them in full, and array shapes and units must be as documented.
"""

import csv
import json
import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import pkm

SOURCE = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PKM = os.environ.get("PKM_BINARY", "pkm")
CH5 = str(SOURCE / "examples" / "machines" / "hexapod_ch5.yaml")
POSE_DEG = [10.0, 0.0, 700.0, 0.0, 5.0, 0.0]
POSE = np.array(POSE_DEG[:3] + list(np.radians(POSE_DEG[3:])))


def cli_json(*args):
    done = subprocess.run([PKM, *map(str, args), "--json"], capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


def close(actual, expected, rel=1e-12, abs_=1e-15):
    np.testing.assert_allclose(np.asarray(actual, dtype=float), np.asarray(expected, dtype=float), rtol=rel,
                               atol=abs_)


@pytest.fixture(scope="module")
def ch5():
    return pkm.Machine.load(CH5)


def test_modes_match_cli(ch5):
    result = pkm.modes(ch5, POSE)
    expected = cli_json("modes", "--machine", CH5, "--pose", ",".join(map(str, POSE_DEG)))
    # The pose is given in degrees to the CLI, so it may differ in the last bit; that moves a frequency
    # by far less than 1e-12 of itself.
    close(result["frequencies_Hz"], expected["frequencies_Hz"], rel=1e-11)
    m = len(expected["frequencies_Hz"])
    assert result["shapes"].shape == (m, m) and result["mass"].shape == (m, m)
    for i, mode in enumerate(expected["modes"]):
        for k, name in enumerate(result["coordinates"]):
            close(result["shapes"][k, i], mode["shape"][name], rel=1e-9, abs_=1e-12)
    close(result["strut_tension_N"], expected["strut_tension_N"], rel=1e-9)
    close(result["static_deflection_mm"], expected["static_deflection_mm"], rel=1e-9, abs_=1e-12)
    assert math.isclose(result["geometric_stiffness_share"], expected["geometric_stiffness_share"], rel_tol=1e-9)
    # ω² are the generalised eigenvalues of K and M: K v = ω² M v for every mode.
    K, M, V = result["stiffness"], result["mass"], result["shapes"]
    omega2 = (2 * np.pi * result["frequencies_Hz"]) ** 2
    np.testing.assert_allclose(K @ V, M @ V * omega2, rtol=1e-8, atol=1e-8 * np.abs(K @ V).max())


def test_compliance_matches_cli(ch5):
    result = pkm.compliance(ch5, POSE)
    expected = cli_json("compliance", "--machine", CH5, "--pose", ",".join(map(str, POSE_DEG)))
    assert result["compliance"].shape == (6, 6)
    close(result["compliance"], expected["compliance"], rel=1e-9, abs_=1e-20)
    assert result["dof"] == expected["dof"]
    close(result["translational_stiffness_N_um"], [p["stiffness_N_um"] for p in expected["translational"]], rel=1e-9)
    close(result["rotational_stiffness_Nm_mrad"], [p["stiffness_Nm_mrad"] for p in expected["rotational"]], rel=1e-9)
    close(result["strut_stiffness_N_mm"], expected["strut_stiffness_N_mm"], rel=1e-9)
    # The weakest stiffness is the inverse of the largest eigenvalue of the translational block (N/mm → N/µm).
    largest = np.linalg.eigvalsh(result["compliance"][:3, :3]).max()
    assert math.isclose(result["translational_stiffness_N_um"][0], 1e-3 / largest, rel_tol=1e-9)


def test_workspace_matches_cli(tmp_path, ch5):
    result = pkm.workspace(ch5, plane="xz", range_mm=100.0, step_mm=20.0)
    expected = cli_json("workspace", "--machine", CH5, "--plane", "xz", "--range-mm", 100, "--step-mm", 20,
                        "--out", tmp_path)
    expected.pop("out")
    summary = result["summary"]
    assert set(expected) <= set(summary)
    assert json.dumps({k: summary[k] for k in expected}, sort_keys=True) == json.dumps(expected, sort_keys=True)
    cells = summary["cells"]
    assert result["pose"].shape == (cells, 6) and result["sensitivity"].shape == (cells, 3)
    assert result["points_per_axis"] == [11, 11]
    with open(tmp_path / "workspace.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == cells
    assert [r["status"] for r in rows] == list(result["status"])
    delta_rho = np.array([float(r["delta_rho"]) if r["delta_rho"] else np.nan for r in rows])
    np.testing.assert_allclose(result["delta_rho"], delta_rho, rtol=1e-5, equal_nan=True)
    np.testing.assert_allclose(result["pose"][:, [0, 2]], [[float(r["x_mm"]), float(r["z_mm"])] for r in rows])
    # δρ is the norm of S_x, S_y, S_z (Smirnov 2019, eq. 145).
    np.testing.assert_allclose(result["delta_rho"], np.linalg.norm(result["sensitivity"], axis=1), rtol=1e-12)


def test_workspace_optional_layers(ch5):
    result = pkm.workspace(ch5, plane="xy", range_mm=20.0, step_mm=20.0, stiffness=True)
    assert result["lowest_stiffness_N_um"].shape == (9,)
    ok = result["status"] == "ok"
    assert ok.any() and (result["lowest_stiffness_N_um"][ok] > 0).all()
    assert "lowest_frequency_Hz" not in result


def test_bad_pose_shape_is_a_value_error(ch5):
    with pytest.raises(ValueError, match=r"expected 6 numbers.*got shape \(3,\)"):
        pkm.compliance(ch5, [0.0, 0.0, 700.0])


def test_pose_out_of_reach_raises_typed_error(ch5):
    # The CLI: "actuator 1 at 4856.329471 mm is above actuator_max 900 mm (hexapod_ch5.yaml:26)".
    with pytest.raises(pkm.LimitExceededError, match="actuator_max"):
        pkm.compliance(ch5, [0.0, 0.0, 5000.0, 0.0, 0.0, 0.0])


def test_modes_without_dynamics_section():
    machine = pkm.Machine.load(str(SOURCE / "examples" / "machines" / "hexapod_genhexkins.yaml"))
    with pytest.raises(pkm.InputError, match="no dynamics: section"):
        pkm.modes(machine, [0.0, 0.0, 508.0, 0.0, 0.0, 0.0])


def test_stiffness_matches_cli(tmp_path, ch5):
    program = str(SOURCE / "examples" / "programs" / "ch5_line.ngc")
    result = pkm.stiffness(ch5, program, "tangential=200,normal=50")
    expected = cli_json("stiffness", program, "--machine", CH5, "--load", "tangential=200,normal=50", "--out",
                        tmp_path)
    assert json.dumps(result["summary"], sort_keys=True) == json.dumps(expected, sort_keys=True)
    points = result["points"]
    assert len(points["normal_mm"]) == expected["points"]
    assert math.isclose(np.abs(points["normal_mm"]).max(), expected["max_normal_deflection_mm"], rel_tol=1e-6)


def test_servo_matches_cli(tmp_path, ch5):
    program = str(SOURCE / "examples" / "programs" / "ch5_line.ngc")
    pkm.plan(ch5, program, out_dir=tmp_path / "plan", tables="csv")
    result = pkm.servo(ch5, tmp_path / "plan", out_dir=tmp_path / "py")
    expected = cli_json("servo", tmp_path / "plan", "--machine", CH5, "--out", tmp_path / "cli")
    written = json.loads((tmp_path / "cli" / "servo_summary.json").read_text())
    assert json.dumps(result["summary"], sort_keys=True) == json.dumps(written, sort_keys=True)
    assert expected["drives"] == written["drives"]
    ticks = result["ticks"]
    assert len(ticks["time_s"]) == len(np.loadtxt(tmp_path / "plan" / "actuators.csv", delimiter=",", skiprows=1))
    assert "contour_error_mm" in ticks and "e1_mm" in ticks


def test_simulate_matches_cli(tmp_path, ch5):
    """pkm.simulate is `pkm simulate`: the same summary; the error's parts add up along the run."""
    program = str(SOURCE / "examples" / "programs" / "ch5_line.ngc")
    pkm.plan(ch5, program, out_dir=tmp_path / "plan", tables="csv")
    result = pkm.simulate(ch5, tmp_path / "plan", load="tangential=200", out_dir=tmp_path / "py")
    cli_json("simulate", tmp_path / "plan", "--machine", CH5, "--load", "tangential=200", "--out", tmp_path / "cli")
    written = json.loads((tmp_path / "cli" / "simulate_summary.json").read_text())
    assert json.dumps(result["summary"], sort_keys=True) == json.dumps(written, sort_keys=True)
    ticks = result["ticks"]
    assert len(ticks["time_s"]) == written["ticks"]
    # Each part is at most the sum of the magnitudes of the others and the total (a vector sum).
    parts = np.stack([ticks[name] for name in ("servo_mm", "elastic_mm", "load_mm", "drives_mm")])
    assert np.all(ticks["contour_error_mm"] <= parts.sum(axis=0) * (1 + 1e-3) + 1e-9)
    assert written["parts"]["load"]["max_mm"] > 0.0


def test_circle_on_the_machine_in_the_loop_matches_cli(tmp_path, ch5):
    """pkm.circle(elastic=True) is `pkm circle --elastic`; a load needs elastic=True."""
    result = pkm.circle(ch5, radius_mm=20.0, feed_mm_min=2400.0, elastic=True, load="tangential=50",
                        out_dir=tmp_path / "py")
    cli_json("circle", "--machine", CH5, "--radius-mm", "20", "--feed-mm-min", "2400", "--elastic", "--load",
             "tangential=50", "--out", tmp_path / "cli")
    written = json.loads((tmp_path / "cli" / "circle_summary.json").read_text())
    assert result["summary"]["machine_in_the_loop"] is True
    for key in ("circular_deviation_ccw_um", "circular_deviation_cw_um", "hysteresis_um"):
        assert result["summary"][key] == written[key], key
    with pytest.raises(ValueError, match="elastic"):
        pkm.circle(ch5, load="tangential=50", out_dir=tmp_path / "refused")


def test_circle_matches_cli(tmp_path, ch5):
    """pkm.circle is `pkm circle`: the same summary and deviations; the ideal drives keep the circle round."""
    result = pkm.circle(ch5, radius_mm=20.0, feed_mm_min=2400.0, out_dir=tmp_path / "py")
    cli_json("circle", "--machine", CH5, "--radius-mm", "20", "--feed-mm-min", "2400", "--out", tmp_path / "cli")
    written = json.loads((tmp_path / "cli" / "circle_summary.json").read_text())
    for key in ("circular_deviation_ccw_um", "circular_deviation_cw_um", "hysteresis_um", "radius_ccw_mm"):
        assert result["summary"][key] == written[key], key
    assert result["summary"]["radius_mm"] == 20.0
    table = np.genfromtxt(tmp_path / "cli" / "circle.csv", delimiter=",", names=True, dtype=None, encoding=None)
    ccw = result["deviations"]["ccw"]
    assert len(ccw["angle_deg"]) == int(np.sum(table["direction"] == "ccw"))
    assert np.all((ccw["angle_deg"] >= 0.0) & (ccw["angle_deg"] < 360.0))
    # The band of the deviations about the common centre holds G about the turn's own centre, nearly.
    band_um = (ccw["radial_deviation_mm"].max() - ccw["radial_deviation_mm"].min()) * 1e3
    assert band_um < 1.0 and result["summary"]["circular_deviation_ccw_um"] < 1.0
