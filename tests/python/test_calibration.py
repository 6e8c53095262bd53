"""pkm.calibrate_plan, pkm.calibrate_simulate and pkm.calibrate_identify against `pkm calibrate` on the shipped
calibration example (examples/calibration/README.md), with the smallest sizes that still exercise every part.

The summaries must equal the CLI's JSON (the same library run; only the paths of the output files differ), the
arrays must equal the CLI's CSV files to the digits they print, and a malformed measurement file must raise
pkm.InputError located at its file, line and column.
"""

import csv
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import pkm

SOURCE = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PKM = os.environ.get("PKM_BINARY", "pkm")
CH5 = str(SOURCE / "examples" / "machines" / "hexapod_ch5.yaml")
EXAMPLE = SOURCE / "examples" / "calibration"
TRACKER = str(EXAMPLE / "hexapod_ch5_tracker.csv")
# Small plans: 12 D-optimal poses from 40 candidates, judged at 5 held-out poses (the CLI's own minimums are
# lower, but 12 poses of 3 targets give 72 equations for the 42 parameters).
PLAN_CLI = ["--poses", "12", "--candidates", "40", "--held-out", "5", "--seed", "3"]
PLAN_PY = dict(poses=12, candidates=40, held_out=5, seed=3)


def cli_json(*args):
    done = subprocess.run([PKM, *map(str, args), "--json"], capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


def csv_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def without(summary, *keys):
    return {k: v for k, v in summary.items() if k not in keys}


@pytest.fixture(scope="module")
def ch5():
    return pkm.Machine.load(CH5)


def test_plan_matches_cli(ch5, tmp_path):
    expected = cli_json("calibrate", "plan", "--machine", CH5, *PLAN_CLI, "--out", tmp_path / "cli")
    result = pkm.calibrate_plan(ch5, **PLAN_PY, out_dir=tmp_path / "py")
    assert result["summary"] == expected
    # The kept files are the CLI's, byte for byte.
    for name in ("plan.csv", "summary.json"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    # Arrays: the poses as plan.csv lists them (deg there, rad here), the parameters as summary.json names them.
    rows = csv_rows(tmp_path / "cli" / "plan.csv")
    assert result["poses"].shape == (12, 6) and len(rows) == 12
    degrees = np.array([[float(r[k]) for k in ("x_mm", "y_mm", "z_mm", "a1_deg", "a2_deg", "a3_deg")] for r in rows])
    np.testing.assert_allclose(result["poses"][:, :3], degrees[:, :3], atol=1e-6)
    np.testing.assert_allclose(np.degrees(result["poses"][:, 3:]), degrees[:, 3:], atol=1e-6)
    assert list(result["plan"]["pose_id"]) == [r["pose_id"] for r in rows]
    assert list(result["parameter_names"]) == [p["name"] for p in expected["parameters"]]
    np.testing.assert_allclose(result["predicted_sigma"], [p["predicted_sd"] for p in expected["parameters"]],
                               rtol=1e-12)
    tool = result["predicted_tool_error_mm"]
    assert tool.shape == (expected["predicted_tool_error_mm"]["held_out_poses"],)
    assert np.isclose(tool.max(), expected["predicted_tool_error_mm"]["max"], rtol=1e-12)
    assert np.isclose(np.sqrt(np.mean(tool**2)), expected["predicted_tool_error_mm"]["rms"], rtol=1e-12)


def test_simulate_matches_cli(ch5, tmp_path):
    # The same file name in two directories: the file names its fixture, written beside it, by that name.
    cli_file, py_file = tmp_path / "cli_m" / "m.csv", tmp_path / "py_m" / "m.csv"
    cli_file.parent.mkdir()
    py_file.parent.mkdir()
    expected = cli_json("calibrate", "simulate", "--machine", CH5, *PLAN_CLI, "--trials", "2",
                        "--write-measurements", cli_file, "--out", tmp_path / "cli")
    result = pkm.calibrate_simulate(ch5, **PLAN_PY, trials=2, write_measurements=py_file, out_dir=tmp_path / "py")
    # The summaries name their files: the same names up to the directories.
    assert json.dumps(result["summary"]).replace("py_m/", "cli_m/") == json.dumps(expected)
    rows = csv_rows(tmp_path / "cli" / "trials.csv")
    assert list(result["trials"]["trial"]) == [int(r["trial"]) for r in rows]
    assert list(result["trials"]["seed"]) == [int(r["seed"]) for r in rows]  # uint64 seeds kept exactly
    assert list(result["trials"]["status"]) == [r["status"] for r in rows]
    np.testing.assert_allclose(result["trials"]["held_out_rms_mm"], [float(r["held_out_rms_mm"]) for r in rows],
                               rtol=1e-8)
    truth = csv_rows(tmp_path / "cli" / "true_parameters.csv")
    assert list(result["true_parameters"]["name"]) == [r["name"] for r in truth]
    np.testing.assert_allclose(result["true_parameters"]["true"], [float(r["true"]) for r in truth], rtol=1e-14)
    # The simulated measurement files differ only in the comment that names the files.
    strip = lambda text: [l for l in text.splitlines() if not l.startswith("# note: true parameters")]
    assert strip(py_file.read_text()) == strip(cli_file.read_text())


def test_identify_matches_cli(ch5, tmp_path):
    calibrated = tmp_path / "cli.yaml"
    expected = cli_json("calibrate", "identify", "--machine", CH5, "--measurements", TRACKER, "--out", calibrated,
                        "--dir", tmp_path / "cli", "--holdout", "3")
    result = pkm.calibrate_identify(ch5, TRACKER, holdout=3)
    assert without(result["summary"], "calibrated_machine") == without(expected, "calibrated_machine")
    params = csv_rows(tmp_path / "cli" / "parameters.csv")
    assert list(result["parameter_names"]) == [p["name"] for p in params]
    assert list(result["parameter_units"]) == [p["unit"] for p in params]
    np.testing.assert_allclose(result["nominal"], [float(p["nominal"]) for p in params], rtol=1e-14)
    np.testing.assert_allclose(result["identified"], [float(p["identified"]) for p in params], rtol=1e-14)
    np.testing.assert_allclose(result["sigma"], [float(p["sigma"]) for p in params], rtol=1e-5)
    assert list(result["identifiable"]) == [p["identifiable"] == "yes" for p in params]
    residuals = csv_rows(tmp_path / "cli" / "residuals.csv")
    np.testing.assert_allclose(result["residuals_before_mm"], [float(r["before_mm"]) for r in residuals], rtol=1e-8)
    np.testing.assert_allclose(result["residuals_after_mm"], [float(r["after_mm"]) for r in residuals], rtol=1e-8)
    # The summary's residual statistics are those of these arrays.
    assert np.isclose(np.sqrt(np.mean(result["residuals_after_mm"] ** 2)), expected["residuals_after"]["rms_mm"],
                      rtol=1e-7)
    # The calibrated machine is the CLI's calibrated file: the same actuators at the measured poses.
    cli_machine = pkm.Machine.load(str(calibrated))
    poses = np.column_stack([result["poses"][k] for k in ("x_mm", "y_mm", "z_mm")] +
                            [np.radians(result["poses"][k]) for k in ("a1_deg", "a2_deg", "a3_deg")])
    np.testing.assert_allclose(result["calibrated_machine"].ik(poses), cli_machine.ik(poses), rtol=0, atol=1e-12)
    assert not np.allclose(ch5.ik(poses), cli_machine.ik(poses), atol=1e-3)  # the calibration changed them


def test_bad_measurement_file_is_located(ch5, tmp_path):
    shutil.copy(EXAMPLE / "plate_fixture.csv", tmp_path / "plate_fixture.csv")
    lines = Path(TRACKER).read_text().splitlines(keepends=True)
    bad_line = next(i for i, l in enumerate(lines) if l.startswith("P01,") and ",S2," in l)  # 0-based
    fields = lines[bad_line].split(",")
    fields[8] = "12x"  # the x of target S2
    lines[bad_line] = ",".join(fields)
    bad = tmp_path / "bad.csv"
    bad.write_text("".join(lines))
    with pytest.raises(pkm.InputError) as caught:
        pkm.calibrate_identify(ch5, bad)
    e = caught.value
    assert e.file == str(bad)
    assert e.line == bad_line + 1
    assert e.column == len(",".join(fields[:8])) + 2  # 1-based, the field after the 8th comma
    assert e.key == "x"
    cli = subprocess.run([PKM, "calibrate", "identify", "--machine", CH5, "--measurements", bad, "--out",
                          tmp_path / "c.yaml"], capture_output=True, text=True)
    assert cli.returncode != 0 and f"{bad}:{e.line}:{e.column}" in cli.stderr + cli.stdout


def test_argument_errors(ch5):
    with pytest.raises(ValueError, match="method"):
        pkm.calibrate_plan(ch5, method="best")
    with pytest.raises(ValueError, match="ballbar"):
        pkm.calibrate_plan(ch5, ballbar_centre_mm=(0, 0, 0), fixture_path=str(EXAMPLE / "plate_fixture.csv"))
    with pytest.raises(ValueError, match="noise_free"):
        pkm.calibrate_simulate(ch5, noise_free=True)
