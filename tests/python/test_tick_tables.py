"""A planned run's servo-rate tables as HDF5 (`pkm plan --tables hdf5`, pkm.plan(tables="hdf5")): DIR/ticks.h5
holds the CSV files' tables as groups and their columns as datasets, which h5py and numpy read as they are, equal
to the CSV to the digits it prints, each with its unit; the file is several times smaller; the report read from it
is the report read from the CSV files, to the digits the CSV prints; a failed run leaves no ticks.h5 behind.
"""

import csv
import json
import math
import os
import re
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest

import pkm

SOURCE = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PKM = os.environ.get("PKM_BINARY", "pkm")
MACHINES = SOURCE / "examples" / "machines"
PROGRAMS = SOURCE / "examples" / "programs"

# What h5py must agree with the CSV to, per column: half the CSV's last printed digit plus half the binary
# quantum (formats/plan_tables.hpp), within one unit of that digit; a relative 5e-4 where the CSV prints in
# scientific notation (3 or 4 decimals of the mantissa), which the file keeps exactly.


def plan_cli(out, *extra):
    return subprocess.run([PKM, "plan", str(PROGRAMS / "pocket.ngc"), "--machine",
                           str(MACHINES / "hexapod_ch5.yaml"), "--out", str(out), "--dynamics", *extra],
                          capture_output=True, text=True)


def read_csv(path):
    """The header, the columns as arrays (NaN for an empty field) and each column's printed digits after the
    point (None: scientific notation)."""
    with open(path) as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    columns, decimals = {}, {}
    for k, name in enumerate(header):
        fields = [r[k] for r in body]
        columns[name] = np.array([float(v) if v != "" else np.nan for v in fields])
        printed = next(v for v in fields if v != "")
        decimals[name] = None if "e" in printed else (len(printed.split(".")[1]) if "." in printed else 0)
    return header, columns, decimals


def assert_table_equals_csv(group, header, columns, decimals):
    assert list(group.keys()) == header  # in the CSV's order: the group tracks its datasets' creation order
    for name in header:
        data = group[name][()]
        expected = columns[name]
        assert data.shape == expected.shape, name
        assert isinstance(group[name].attrs["unit"], str), name
        if name == "line":
            assert data.dtype == np.int64
            assert np.array_equal(data, expected.astype(np.int64))
            continue
        assert data.dtype == np.float64, name
        finite = np.isfinite(expected)
        assert np.array_equal(finite, np.isfinite(data)), name  # NaN where the CSV field is empty
        if decimals[name] is None:
            np.testing.assert_allclose(data[finite], expected[finite], rtol=5.01e-4, atol=1e-300, err_msg=name)
        else:
            np.testing.assert_allclose(data[finite], expected[finite], rtol=0, atol=1.01 * 10.0 ** -decimals[name],
                                       err_msg=name)


def test_the_hdf5_tables_are_the_csv_tables_with_units_and_smaller(tmp_path):
    as_csv, as_hdf5 = tmp_path / "csv", tmp_path / "hdf5"
    done = plan_cli(as_csv, "--tables", "csv")
    assert done.returncode == 0, done.stderr
    assert not (as_csv / "ticks.h5").exists()
    done = plan_cli(as_hdf5)  # the default
    assert done.returncode == 0, done.stderr
    assert done.returncode == 0, done.stderr
    assert not (as_hdf5 / "actuators.csv").exists() and not (as_hdf5 / "path.csv").exists()
    summary_csv = json.loads((as_csv / "summary.json").read_text())
    summary_hdf5 = json.loads((as_hdf5 / "summary.json").read_text())
    assert summary_hdf5["ticks"] == summary_csv["ticks"]
    csv_bytes = 0
    with h5py.File(as_hdf5 / "ticks.h5", "r") as f:
        assert set(f.keys()) == {"actuators", "path", "forces"}
        assert f.attrs["pkm_version"] == pkm.__version__
        for table in ("actuators", "path", "forces"):
            header, columns, decimals = read_csv(as_csv / f"{table}.csv")
            csv_bytes += (as_csv / f"{table}.csv").stat().st_size
            assert len(columns["time_s"]) == summary_csv["ticks"] or table == "forces"
            assert_table_equals_csv(f[table], header, columns, decimals)
        assert f["actuators"]["q1_mm"].attrs["unit"] == "mm"
        assert f["path"]["a_abc_deg"].attrs["unit"] == "deg"
        assert f["path"]["path_speed_mm_s"].attrs["unit"] == "mm/s"
        assert f["forces"]["power1_W"].attrs["unit"] == "W"
        # Stored shuffled and deflated, in chunks.
        assert f["path"]["x_program_mm"].compression == "gzip" and f["path"]["x_program_mm"].shuffle
    ratio = csv_bytes / (as_hdf5 / "ticks.h5").stat().st_size
    print(f"CSV {csv_bytes} bytes, ticks.h5 {(as_hdf5 / 'ticks.h5').stat().st_size} bytes: {ratio:.1f}x smaller")
    assert ratio >= 3.0


def test_pkm_plan_writes_the_same_file_and_its_arrays_match_it(tmp_path):
    machine = pkm.Machine.load(str(MACHINES / "hexapod_ch5.yaml"))
    result = pkm.plan(machine, str(PROGRAMS / "pocket.ngc"), out_dir=str(tmp_path), tables="hdf5")
    with h5py.File(tmp_path / "ticks.h5", "r") as f:
        q = np.column_stack([f["actuators"][f"q{j}_mm"][()] for j in range(1, 7)])
        xyz = np.column_stack([f["path"][c][()] for c in ("x_program_mm", "y_program_mm", "z_program_mm")])
    # Rounded to 2^-20 mm: within half of it of the full-precision arrays.
    np.testing.assert_allclose(q, result["actuators_mm"], rtol=0, atol=2.0 ** -21)
    np.testing.assert_allclose(xyz, result["xyz_program_mm"], rtol=0, atol=2.0 ** -21)
    with pytest.raises(ValueError, match="tables 'parquet'"):
        pkm.plan(machine, str(PROGRAMS / "pocket.ngc"), out_dir=str(tmp_path), tables="parquet")


def report_data(page):
    """The report's data, as the page embeds it (report/report_html.cpp)."""
    text = page.read_text()
    opening = '<script type="application/json" id="pkm-report-data">'
    start = text.index(opening) + len(opening)
    return json.loads(text[start:text.index("</script>", start)])


NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def report_tolerances(period_s, ticks):
    """How far a number of the report may be from the CSV report's, per chart (else the default): the CSV's last
    printed digit and half the HDF5 quantum of a table's column (formats/plan_tables.hpp) each move a value by at
    most that digit, 1e-6 for positions and times, 1e-4 for speeds and forces; a speed or acceleration that the
    report takes from differences of positions moves by 2 or 4 of them over the period (squared); the energy
    sums the powers' 5 decimals over every tick; the exact columns (path and tool errors) by the CSV's significant
    digits, relatively. On top of that, the report's own last printed digit (6 significant digits)."""
    position = 1e-6
    return {
        "default": (position, 0.0),
        "actuator_speeds": (2 * position / period_s, 0.0),
        "actuator_accels": (4 * position / period_s ** 2, 0.0),
        "path_speed": (1e-4, 0.0),
        "contour_error": (1e-12, 5.01e-4),  # path.csv's path error: 4 significant digits
        "dynamic_error": (1e-12, 5.01e-5),  # response.csv: 4 decimals of the mantissa
        "drive_forces": (1e-4, 0.0),
        "drive_forces_static": (1e-4, 0.0),
        "drive_forces_dynamic": (1e-4, 0.0),
        "drive_power": (7 * 1e-5, 0.0),
        "drive_energy": (6 * 1e-5 * period_s * ticks, 0.0),
    }


def assert_reports_agree(a, b, tolerance, where="report"):
    """Equal structure, equal text, numbers (also those inside text) within `tolerance` = (absolute, relative) plus
    one unit of the sixth significant digit; a dict of tolerances gives each key of a dict its own ("default" for
    the others)."""
    assert type(a) is type(b) or (isinstance(a, (int, float)) and isinstance(b, (int, float))), where
    if isinstance(a, dict):
        assert a.keys() == b.keys(), where
        for key in a:
            inner = tolerance.get(key, tolerance["default"]) if isinstance(tolerance, dict) else tolerance
            assert_reports_agree(a[key], b[key], inner, f"{where}.{key}")
    elif isinstance(a, list):
        assert len(a) == len(b), where
        for k, (x, y) in enumerate(zip(a, b)):
            assert_reports_agree(x, y, tolerance, f"{where}[{k}]")
    elif isinstance(a, str):
        assert NUMBER.split(a) == NUMBER.split(b), f"{where}: {a!r} != {b!r}"
        for x, y in zip(NUMBER.findall(a), NUMBER.findall(b)):
            assert_reports_agree(float(x), float(y), tolerance, f"{where}: {a!r} != {b!r}")
    elif isinstance(a, (int, float)) and not isinstance(a, bool):
        absolute, relative = tolerance
        scale = max(abs(a), abs(b))
        digit = 10.0 ** (math.floor(math.log10(scale)) - 5) if scale > 0 else 0.0
        assert abs(a - b) <= absolute + relative * scale + 1.01 * digit, f"{where}: {a} != {b}"
    else:
        assert a == b, where


def bucket_extremes(series):
    """The series with each bucket's two points (report/decimator.hpp: its minimum and maximum, in the order they
    occurred) as (smaller, larger): where a bucket's values are level, the tables' last digit may turn which of
    the two came first."""
    out = []
    for one in series:
        values = one["values"]
        pairs = [values[k:k + 2] for k in range(0, len(values), 2)]
        out.append({**one, "values": [sorted(p) if None not in p else p for p in pairs]})
    return out


def test_the_report_of_the_hdf5_tables_is_the_report_of_the_csv_tables(tmp_path):
    runs = {}
    for form in ("csv", "hdf5"):
        out = tmp_path / form
        done = plan_cli(out, "--tables", form, "--report", str(out / "report.html"))
        assert done.returncode == 0, done.stderr
        runs[form] = report_data(out / "report.html")
    assert (tmp_path / "hdf5" / "ticks.h5").exists() and not (tmp_path / "hdf5" / "path.csv").exists()
    csv_report, hdf5_report = runs["csv"], runs["hdf5"]
    ticks, rate_hz = csv_report["summary"]["ticks"], csv_report["summary"]["rate_hz"]
    assert ticks > 10000  # many blocks of the HDF5 reader's rows
    tolerances = report_tolerances(1.0 / rate_hz, ticks)
    charts = {chart["id"]: chart for chart in csv_report["charts"]}
    assert {"actuator_accels", "drive_forces", "drive_energy"} <= charts.keys()  # with --dynamics
    assert [c["id"] for c in hdf5_report["charts"]] == [c["id"] for c in csv_report["charts"]]
    for mine, theirs in zip(hdf5_report["charts"], csv_report["charts"]):
        tolerance = tolerances.get(mine["id"], tolerances["default"])
        assert_reports_agree(mine["x"], theirs["x"], tolerances["default"], f"{mine['id']}.x")
        assert_reports_agree(bucket_extremes(mine["series"]), bucket_extremes(theirs["series"]), tolerance,
                             mine["id"])
    # The scene prints positions to 0.1 µm, the limit closeness to 1e-3, errors to 3 and forces to 4 significant
    # digits (report/scene.cpp): one unit of that last digit, on top of what moves the values. The closeness of
    # a drive is its largest ratio to a limit, speeds' and accelerations' included.
    limits = csv_report["summary"]["limits"]
    speeds, accels = tolerances["actuator_speeds"][0], tolerances["actuator_accels"][0]
    closeness = 1e-3 + max(speeds / limits["actuator_speed"], accels / limits["actuator_accel"])
    at_tenth_um, three_digits = (1e-4 + 1e-6, 0.0), (1e-300, 1.01e-2)
    scene = {"default": tolerances["default"], "executed_path": at_tenth_um, "programmed_path": at_tenth_um,
             "base_polygon": at_tenth_um, "executed_error_mm": three_digits, "error_scale_mm": three_digits,
             "drive_force_scale": (1e-4, 1.01e-3),
             "frames": {"default": at_tenth_um, "time_s": tolerances["default"], "line": (0.0, 0.0),
                        "strut_closeness": (closeness, 0.0), "drive_force": (1e-4, 1.01e-3)}}
    # The limits reached name the peaks of speed and acceleration, which move as their charts do.
    rest = {key: value for key, value in csv_report.items() if key != "charts"}
    assert_reports_agree({key: hdf5_report[key] for key in rest}, rest,
                         {"default": tolerances["default"], "scene": scene,
                          "limits_reached": tolerances["actuator_accels"]})


def test_an_unknown_table_form_is_refused_naming_the_choices(tmp_path):
    done = plan_cli(tmp_path / "run", "--tables", "parquet")
    assert done.returncode != 0
    assert "--tables: parquet not in {csv,hdf5}" in done.stderr, done.stderr
    assert not (tmp_path / "run").exists()


def test_a_failed_run_leaves_no_ticks_file(tmp_path):
    program = tmp_path / "far.ngc"
    # Half the way in bounds, then far outside the machine's reach: refused during the run.
    program.write_text("G21 G90 G94\nG1 X0 Y0 Z0 F600\nG1 X5 F600\nG1 X5000 F600\nM2\n")
    out = tmp_path / "run"
    done = subprocess.run([PKM, "plan", str(program), "--machine", str(MACHINES / "hexapod_ch5.yaml"), "--out",
                           str(out), "--tables", "hdf5"], capture_output=True, text=True)
    assert done.returncode != 0
    assert not (out / "ticks.h5").exists()
    assert not out.exists() or not any(p.name.endswith(".h5") for p in out.rglob("*"))
