"""pkm.interpret, pkm.plan, pkm.interpolate and pkm.optimize against the CLI on the shipped examples.

The CLI ($PKM_BINARY) and the module run the same library; the summaries must agree to 1e-12 and the arrays
must agree with the CSVs the CLI writes (to their printed precision) and with the summaries' own extremes.
"""

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
MACHINES = SOURCE / "examples" / "machines"
PROGRAMS = SOURCE / "examples" / "programs"


def machine_path(name):
    return str(MACHINES / f"{name}.yaml")


def program_path(name):
    return str(PROGRAMS / name)


def cli(*args):
    done = subprocess.run([PKM, *map(str, args)], capture_output=True, text=True, check=True)
    return done.stdout


def assert_same(actual, expected, where="summary", skip=()):
    """Equal JSON-like values: numbers to 1e-12 (relative), everything else exactly."""
    if isinstance(expected, dict):
        assert isinstance(actual, dict), where
        keys = set(expected) - set(skip)
        assert keys <= set(actual), f"{where}: missing {sorted(keys - set(actual))}"
        for key in keys:
            assert_same(actual[key], expected[key], f"{where}.{key}", skip)
    elif isinstance(expected, list):
        assert len(actual) == len(expected), where
        for i, (a, e) in enumerate(zip(actual, expected)):
            assert_same(a, e, f"{where}[{i}]", skip)
    elif isinstance(expected, float) or isinstance(actual, float):
        assert math.isclose(actual, expected, rel_tol=1e-12, abs_tol=1e-12), f"{where}: {actual} != {expected}"
    else:
        assert actual == expected, f"{where}: {actual!r} != {expected!r}"


@pytest.fixture(scope="module")
def ch5():
    return pkm.Machine.load(machine_path("hexapod_ch5"))


# --- interpret ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("program", ["circle.ngc", "pocket.ngc", "ball_end_5axis.cl"])
def test_interpret_matches_cli(program):
    moves = pkm.interpret(program_path(program))
    expected = json.loads(cli("interpret", program_path(program), "--json"))["moves"]
    assert len(moves["line"]) == len(expected) > 0
    assert moves["end_mm"].shape == (len(expected), 3) and moves["end_mm"].dtype == np.float64
    for i, e in enumerate(expected):
        assert moves["line"][i] == e["line"]
        assert moves["kind"][i] == e["kind"]
        np.testing.assert_array_equal(np.concatenate([moves["end_mm"][i], moves["end_abc_deg"][i]]), e["end"])
        assert moves["feed_mm_min"][i] == e["feed_mm_min"]
        assert (moves["source_file"][i], moves["source_line"][i]) == (e["file"], e["source_line"])
        np.testing.assert_array_equal(moves["program_end_mm"][i], e["program_end"][:3])
        assert moves["frame"][i] == e["frame"]["index"]
        if e["kind"] == "arc":
            np.testing.assert_array_equal(moves["center_mm"][i], e["center"])
            np.testing.assert_array_equal(moves["normal"][i], e["normal"])
            assert moves["turns"][i] == e["turns"]
        else:
            assert np.isnan(moves["center_mm"][i]).all()
        if "dwell_s" in e:
            assert moves["dwell_s"][i] == e["dwell_s"]


def test_interpret_takes_the_subroutine_path_and_parameter_file_keywords(tmp_path):
    # A list, a path-like and LinuxCNC's colon-separated string are all accepted; a program that calls no
    # subroutine reads the same with any of them.
    plain = pkm.interpret(program_path("circle.ngc"))
    for folders in ([tmp_path, str(PROGRAMS)], tmp_path, f"{tmp_path}:{PROGRAMS}"):
        moves = pkm.interpret(program_path("circle.ngc"), subroutine_path=folders)
        np.testing.assert_array_equal(moves["end_mm"], plain["end_mm"])
    with pytest.raises(TypeError):
        pkm.interpret(program_path("circle.ngc"), subroutine_path=42)


def test_interpret_names_the_format_and_takes_the_format_keywords():
    # The example CL program is NX CLSF by its content; forced to G-code it is refused, and an unknown key is
    # a ValueError naming the keys.
    moves = pkm.interpret(program_path("ball_end_5axis.cl"))
    assert moves["format"] == "NX CLSF"
    assert pkm.interpret(program_path("circle.ngc"))["format"] == "G-code (RS274/NGC)"
    kept = pkm.interpret(program_path("ball_end_5axis.cl"), format="apt", transform=False)
    assert kept["format"] == "APT CL data"
    np.testing.assert_array_equal(kept["tool_axis"], moves["tool_axis"])  # MSYS is the identity there
    with pytest.raises(pkm.ProgramError):
        pkm.interpret(program_path("ball_end_5axis.cl"), format="gcode")
    with pytest.raises(ValueError, match="one of auto, gcode"):
        pkm.interpret(program_path("circle.ngc"), format="mastercam")


def test_interpret_with_machine_starts_at_its_home(ch5):
    # ch5's program zero is its home tool point, so the start is program zero either way; the moves agree.
    alone = pkm.interpret(program_path("ch5_line.ngc"))
    planned = pkm.interpret(program_path("ch5_line.ngc"), ch5)
    np.testing.assert_array_equal(planned["start_mm"], [0.0, 0.0, 0.0])
    np.testing.assert_array_equal(planned["end_mm"], alone["end_mm"])


def test_program_error_has_line_and_column(tmp_path):
    bad = tmp_path / "bad.ngc"
    bad.write_text("G21 G90\nG1 X10 F100\nG1 X20 Y\nM2\n")
    with pytest.raises(pkm.ProgramError) as caught:
        pkm.interpret(bad)
    error = caught.value
    # The CLI says where, as rs274 reads it: "bad.ngc:3:9: No characters found in reading real value".
    completed = subprocess.run([PKM, "interpret", str(bad)], capture_output=True, text=True)
    assert completed.returncode != 0
    assert f"{bad}:{error.line}:{error.column}:" in completed.stderr
    assert (error.file, error.line, error.column) == (str(bad), 3, 9)
    assert isinstance(error, ValueError)


def test_missing_program_is_a_file_error(tmp_path):
    with pytest.raises(pkm.FileIOError):
        pkm.interpret(tmp_path / "absent.ngc")


# --- plan --------------------------------------------------------------------------------------------------

PLAN_PAIRS = [("hexapod_ch5", "ch5_line.ngc"), ("planar3", "planar_circle.ngc"),
              ("hexapod_ch3", "hexapod_circle.ngc")]


@pytest.mark.parametrize("machine_name,program", PLAN_PAIRS)
def test_plan_summary_and_arrays_match_cli(tmp_path, machine_name, program):
    machine = pkm.Machine.load(machine_path(machine_name))
    result = pkm.plan(machine, program_path(program))
    cli("plan", program_path(program), "--machine", machine_path(machine_name), "--tables", "csv", "--out", tmp_path)
    expected = json.loads((tmp_path / "summary.json").read_text())
    summary = result["summary"]
    assert_same(summary, expected)

    ticks = summary["ticks"]
    unit = summary["actuator_unit"]
    key = "actuators_mm" if unit == "mm" else "actuators_rad"
    q = result[key]
    n = len(summary["actuators"])
    assert q.shape == (ticks, n) and result["pose_machine"].shape == (ticks, 6) and result["time_s"].shape == (ticks,)
    np.testing.assert_allclose(np.diff(result["time_s"]), 1.0 / summary["rate_hz"], rtol=0, atol=1e-12)
    # The summary's extremes are those of the arrays.
    scale = 1.0 if unit == "mm" else 180.0 / math.pi
    for j, a in enumerate(summary["actuators"]):
        assert math.isclose(q[:, j].min() * scale, a["min_position"], rel_tol=1e-12)
        assert math.isclose(q[:, j].max() * scale, a["max_position"], rel_tol=1e-12)
    assert math.isclose(np.nanmax(result["path_error_mm"]), summary["max_path_error_mm"], rel_tol=1e-12)
    # actuators.csv holds the same ticks at six decimals.
    csv = np.loadtxt(tmp_path / "actuators.csv", delimiter=",", skiprows=1)
    assert csv.shape == (ticks, n + 1)
    np.testing.assert_allclose(csv[:, 0], result["time_s"], atol=6e-7)
    np.testing.assert_allclose(csv[:, 1:], q * scale, atol=6e-7)
    lines = np.loadtxt(tmp_path / "path.csv", delimiter=",", skiprows=1, usecols=1, dtype=np.int64)
    np.testing.assert_array_equal(lines, result["line"])
    # path.csv's pose columns are the program coordinates, named by their frame as the dict's keys are.
    with open(tmp_path / "path.csv") as f:
        header = f.readline().strip().split(",")
    assert header[3:9] == ["x_program_mm", "y_program_mm", "z_program_mm", "a_abc_deg", "b_abc_deg", "c_abc_deg"]
    path = np.loadtxt(tmp_path / "path.csv", delimiter=",", skiprows=1, usecols=range(3, 9), ndmin=2)
    np.testing.assert_allclose(path[:, :3], result["xyz_program_mm"], atol=6e-7)
    np.testing.assert_allclose(path[:, 3:], result["abc_deg"], atol=6e-7)


def test_plan_options_match_cli(tmp_path, ch5):
    result = pkm.plan(ch5, program_path("circle.ngc"), servo_period_ms=2.0, feed_override_pct=50.0,
                      blend_tolerance_mm=0.05, path_error=False)
    cli("plan", program_path("circle.ngc"), "--machine", machine_path("hexapod_ch5"), "--rate", 500,
        "--override", 50, "--tolerance", 0.05, "--no-path-error", "--out", tmp_path)
    expected = json.loads((tmp_path / "summary.json").read_text())
    assert_same(result["summary"], expected)
    assert result["summary"]["rate_hz"] == 500.0
    assert np.isnan(result["path_error_mm"]).all()


def test_plan_with_a_law_matches_cli(tmp_path):
    machine = pkm.Machine.load(machine_path("planar3"))
    result = pkm.plan(machine, program_path("planar_circle.ngc"), law="increment")
    printed = json.loads(cli("plan", program_path("planar_circle.ngc"), "--machine", machine_path("planar3"),
                             "--law", "increment", "--out", tmp_path, "--json"))
    assert_same(result["summary"], json.loads((tmp_path / "summary.json").read_text()))
    assert_same(result["law"], printed["redundancy"], skip={"seconds"})
    # The law turns the platform (φ, the third angle); the program as written holds it constant.
    assert np.ptp(result["pose_machine"][:, 5]) > 1e-3
    assert np.ptp(pkm.plan(machine, program_path("planar_circle.ngc"))["pose_machine"][:, 5]) < 1e-12


def test_plan_writes_the_cli_files_when_asked(tmp_path, ch5):
    result = pkm.plan(ch5, program_path("ch5_line.ngc"), out_dir=tmp_path / "run")
    written = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert_same(result["summary"], written)
    # The servo-rate tables as ticks.h5 unless tables="csv" (as pkm plan --tables).
    assert (tmp_path / "run" / "ticks.h5").exists() and not (tmp_path / "run" / "actuators.csv").exists()
    pkm.plan(ch5, program_path("ch5_line.ngc"), out_dir=tmp_path / "csv", tables="csv")
    assert (tmp_path / "csv" / "actuators.csv").exists() and not (tmp_path / "csv" / "ticks.h5").exists()


def test_plan_dynamics_matches_cli(tmp_path, ch5):
    result = pkm.plan(ch5, program_path("ch5_line.ngc"), dynamics=True)
    cli("plan", program_path("ch5_line.ngc"), "--machine", machine_path("hexapod_ch5"), "--dynamics", "--tables",
        "csv", "--out", tmp_path)
    expected = json.loads((tmp_path / "summary.json").read_text())
    assert_same(result["summary"], expected)
    d = result["dynamics"]
    ticks = result["summary"]["ticks"]
    assert d["force_N"].shape == (ticks, 6) and d["power_W"].shape == (ticks, 6)
    np.testing.assert_array_equal(d["time_s"], result["time_s"])
    np.testing.assert_allclose(d["force_N"], d["static_force_N"] + d["dynamic_force_N"], rtol=1e-12, atol=1e-9)
    for j, drive in enumerate(result["summary"]["dynamics"]["drives"]):
        assert math.isclose(np.abs(d["force_N"][:, j]).max(), drive["peak_force_N"], rel_tol=1e-12)
    forces = np.loadtxt(tmp_path / "forces.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(forces[:, 2:20:3], d["force_N"], atol=6e-5)


def test_plan_dynamics_without_a_dynamics_section():
    machine = pkm.Machine.load(machine_path("hexapod_genhexkins"))
    with pytest.raises(pkm.InputError) as caught:
        pkm.plan(machine, program_path("ch5_line.ngc"), dynamics=True)
    assert caught.value.key == "dynamics"
    assert "dynamics" in str(caught.value)


def test_plan_rejects_bad_options(ch5):
    with pytest.raises(ValueError):
        pkm.plan(ch5, program_path("ch5_line.ngc"), feed_override_pct=0.0)
    with pytest.raises(pkm.InputError):
        pkm.plan(ch5, program_path("ch5_line.ngc"), law="fastest")


# --- interpolate -------------------------------------------------------------------------------------------

def test_interpolate_matches_cli(tmp_path, ch5):
    result = pkm.interpolate(ch5, program_path("ch5_line.ngc"))
    cli("interpolate", program_path("ch5_line.ngc"), "--machine", machine_path("hexapod_ch5"), "--out", tmp_path)
    expected = json.loads((tmp_path / "summary.json").read_text())
    timing = [k for k in expected if "compute_us" in k or k.startswith("period_time")]
    assert_same(result["summary"], expected, skip=timing)
    periods = expected["periods"]
    assert result["steps"].shape == (periods, 6) and result["steps"].dtype == np.int32
    steps = np.loadtxt(tmp_path / "steps.csv", delimiter=",", skiprows=1).astype(np.int64)
    np.testing.assert_array_equal(steps[:, 3:9], result["steps"])
    np.testing.assert_array_equal(steps[:, 9:15], result["position_steps"])
    np.testing.assert_array_equal(steps[:, 2], result["line"])
    ends = [a["end_position_steps"] for a in expected["actuators"]]
    np.testing.assert_array_equal(result["position_steps"][-1], ends)
    assert math.isclose(result["contour_error_mm"].max(), expected["max_contour_error_mm"], rel_tol=1e-12)


# --- optimize ----------------------------------------------------------------------------------------------

def test_optimize_matches_cli(tmp_path):
    machine = pkm.Machine.load(machine_path("planar3"))
    out = tmp_path / "py.ngc"
    result = pkm.optimize(machine, program_path("planar_circle.ngc"), "increment", out_path=out)
    expected = json.loads(cli("optimize", program_path("planar_circle.ngc"), "--machine", machine_path("planar3"),
                              "--law", "increment", "--out", tmp_path / "cli.ngc", "--json"))
    assert_same(result["summary"], expected, skip={"seconds", "out", "machine"})
    assert out.read_text() == (tmp_path / "cli.ngc").read_text()
    s = result["summary"]
    chosen = result["chosen"]
    assert chosen["increment_sum_mm"] == s["opt_sum_mm"]
    assert result["constant"]["increment_sum_mm"] == s["const_sum_mm"]
    assert math.isclose(chosen["max_increment_mm"].sum(), s["opt_sum_mm"], rel_tol=1e-9)
    k = len(s["free_coordinates"])
    assert result["free_rad"].shape == (s["points"], k)
    lo, hi = np.radians(np.array(s["free_range_deg"]).T)
    assert (result["free_rad"] >= lo - 1e-12).all() and (result["free_rad"] <= hi + 1e-12).all()


def test_optimize_adaptive_parts_match_cli(tmp_path):
    """parts='adaptive' is `pkm optimize --parts adaptive`: the same summary and program; the arrays hold the
    motion between the written parts' ends, sampled at step_mm."""
    machine = pkm.Machine.load(machine_path("planar3"))
    out = tmp_path / "py.ngc"
    result = pkm.optimize(machine, program_path("planar_circle.ngc"), "increment", parts="adaptive", step_mm=0.5,
                          improvement=0.005, patience=2, out_path=out)
    expected = json.loads(cli("optimize", program_path("planar_circle.ngc"), "--machine", machine_path("planar3"),
                              "--law", "increment", "--parts", "adaptive", "--step-mm", "0.5", "--improvement",
                              "0.005", "--patience", "2", "--out", tmp_path / "cli.ngc", "--json"))
    assert_same(result["summary"], expected, skip={"seconds", "out", "machine"})
    assert out.read_text() == (tmp_path / "cli.ngc").read_text()
    s = result["summary"]
    assert s["parts"] == "adaptive" and s["patience"] == 2
    assert 2 <= s["parts_written"] < s["points"] - 1
    assert result["free_rad"].shape == (s["points"], 1)
    assert math.isclose(result["chosen"]["max_increment_mm"].sum(), s["opt_sum_mm"], rel_tol=1e-9)
    steps = np.linalg.norm(np.diff(result["position_mm"], axis=0), axis=1)
    assert steps.max() <= 0.5 + 1e-9
    with pytest.raises(ValueError, match="parts"):
        pkm.optimize(machine, program_path("planar_circle.ngc"), "increment", parts="some")


def test_optimize_bounds_each_angle_as_the_cli(tmp_path):
    """bounds_deg=((lo, hi), ...) bounds each of the three angles, as `--bounds LO,HI,LO,HI,LO,HI`."""
    machine = pkm.Machine.load(machine_path("hexapod_ch3"))
    each = ((-5.0, 5.0), (-5.0, 5.0), (-20.0, 20.0))
    result = pkm.optimize(machine, program_path("hexapod_circle.ngc"), "increment", free="all", bounds_deg=each,
                          step_mm=5.0)
    expected = json.loads(cli("optimize", program_path("hexapod_circle.ngc"), "--machine", machine_path("hexapod_ch3"),
                              "--law", "increment", "--free", "all", "--bounds", "-5,5,-5,5,-20,20", "--step-mm", "5",
                              "--out", tmp_path / "cli.ngc", "--json"))
    assert_same(result["summary"], expected, skip={"seconds", "out", "machine"})
    assert result["summary"]["bounds_deg"] == [list(b) for b in each]
    lo, hi = np.radians(np.array(each).T)
    assert (result["free_rad"] >= lo - 1e-12).all() and (result["free_rad"] <= hi + 1e-12).all()
    with pytest.raises(TypeError, match="bounds_deg"):
        pkm.optimize(machine, program_path("hexapod_circle.ngc"), "increment", free="all", bounds_deg="wide")
    with pytest.raises(ValueError, match="2 ranges"):
        pkm.optimize(machine, program_path("hexapod_circle.ngc"), "increment", free="all", bounds_deg=each[:2])


def test_optimize_glide_scenarios_measure_rotation_and_limit_margin(tmp_path):
    """The rotation law turns the hexaglide's platform no more than holding the spin; the potential law keeps the
    carriages at least as far from their limits as the increment law; both metrics are in every run's dicts."""
    machine = pkm.Machine.load(machine_path("hexaglide"))
    program = program_path("hexapod_tilt.ngc")
    runs = {law: pkm.optimize(machine, program, law, solver="global") for law in ("increment", "rotation", "potential")}
    for law, run in runs.items():
        for metrics in (run["chosen"], run["constant"]):
            assert metrics["rotation_sum_deg"] > 0.0, law
            assert 0.0 < metrics["min_limit_margin"] <= 0.5, law
        assert run["summary"]["rotation_opt_deg"] == run["chosen"]["rotation_sum_deg"]
    assert runs["rotation"]["chosen"]["rotation_sum_deg"] <= runs["rotation"]["constant"]["rotation_sum_deg"] + 1e-9
    assert runs["rotation"]["chosen"]["rotation_sum_deg"] <= runs["increment"]["chosen"]["rotation_sum_deg"] + 1e-9
    assert runs["potential"]["chosen"]["min_limit_margin"] >= runs["increment"]["chosen"]["min_limit_margin"]


def straight_then_reversal(tmp_path):
    """160 moves of 0.5 mm at the ch5 hexapod's fastest feed, then straight back (a stop)."""
    lines = ["G21 G90 G17 G94", "G0 X-40 Y0 Z0", "G1 F6000"]
    lines += [f"G1 X{-40.0 + 0.5 * k:.1f}" for k in range(1, 161)]
    lines += ["G1 X-40", "M2"]
    path = tmp_path / "straight.ngc"
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def test_plan_look_ahead_window_binds_slower_and_says_so(tmp_path, ch5):
    program = straight_then_reversal(tmp_path)
    whole = pkm.plan(ch5, program)
    windowed = pkm.plan(ch5, program, lookahead_moves=4)
    assert whole["summary"]["lookahead_binding"] == 0
    assert windowed["summary"]["lookahead_binding"] > 0
    assert any("look-ahead window" in w for w in windowed["summary"]["warnings"])
    assert not any("look-ahead window" in w for w in whole["summary"]["warnings"])
    assert windowed["summary"]["duration_s"] > whole["summary"]["duration_s"]
    assert windowed["summary"]["max_path_speed_mm_s"] < whole["summary"]["max_path_speed_mm_s"]
    # The CLI's options give the same plan.
    out = tmp_path / "cli"
    cli("plan", program, "--machine", machine_path("hexapod_ch5"), "--out", out, "--lookahead-moves", 4)
    assert_same(windowed["summary"], json.loads((out / "summary.json").read_text()))
    with pytest.raises(ValueError, match="lookahead"):
        pkm.plan(ch5, program, lookahead_mm=0.0)
