"""A planned run's servo-rate tables as HDF5 (`pkm plan --tables hdf5`, pkm.plan(tables="hdf5")): DIR/ticks.h5
holds the CSV files' tables as groups and their columns as datasets, which h5py and numpy read as they are, equal
to the CSV to the digits it prints, each with its unit; the file is several times smaller; the report, which reads
the CSV files, is refused with it; a failed run leaves no ticks.h5 behind.
"""

import csv
import json
import os
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
    assert list(group.keys()) == sorted(header)  # h5py lists a group's datasets by name
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
    done = plan_cli(as_csv)
    assert done.returncode == 0, done.stderr
    done = plan_cli(as_hdf5, "--tables", "hdf5")
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


def test_the_report_is_refused_with_hdf5_tables_and_nothing_is_written(tmp_path):
    out = tmp_path / "run"
    done = plan_cli(out, "--tables", "hdf5", "--report", str(tmp_path / "report.html"))
    assert done.returncode != 0
    assert "--tables" in done.stderr and "--report" in done.stderr, done.stderr
    assert not out.exists() and not (tmp_path / "report.html").exists()


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
