"""The Python examples (examples/python/*.py) run with --quick: each writes its PNG and JSON, and its key numbers
agree with what they show (the trend and Table 2 of Smirnov 2019, §3.5.1, a sane δρ map, an interior layout
optimum)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import pkm

SOURCE = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def run_example(name, out, *extra):
    completed = subprocess.run([sys.executable, str(SOURCE / "examples/python" / f"{name}.py"), "--quick",
                                "--out", str(out), *extra], capture_output=True, text=True, timeout=300,
                               cwd=SOURCE, env=dict(os.environ))
    assert completed.returncode == 0, completed.stderr
    png = out / f"{name}.png"
    assert png.read_bytes()[:8] == PNG_SIGNATURE and png.stat().st_size > 10_000
    return json.loads((out / f"{name}.json").read_text()), completed.stdout


def test_v7_separation_study(tmp_path):
    summary, stdout = run_example("v7_separation", tmp_path)
    delta = summary["separation_deg"]
    const, greedy = np.array(summary["const_sum_mm"]), np.array(summary["greedy_sum_mm"])
    assert delta == [0.0, 15.0, 30.0]
    # The optimiser's held-constant sum is the one batch IK gives along the same 1° points.
    assert np.allclose(const, summary["ik_const_sum_mm"], rtol=0, atol=1e-6)
    # The dissertation's trend: separating the pairs shortens both sums, and the law never makes a path slower.
    assert (greedy <= const + 1e-9).all()
    assert (np.diff(const) < 0).all() and (np.diff(greedy) < 0).all()
    # Table 2: constant within 1 mm of the printed sum; the optimum at most the printed one + 1 mm.
    assert abs(const[0] - 148.6) <= 1.0 and abs(const[2] - 126.0) <= 1.0
    assert greedy[2] <= 85.0 + 1.0
    assert (np.array(summary["largest_angle_deg"]) <= 10.0 + 1e-9).all()
    assert "greedy_mm" in stdout


def test_workspace_delta_rho_map(tmp_path):
    summary, _ = run_example("workspace_delta_rho", tmp_path)
    assert summary["points"] == 41 * 41
    assert 0.2 < summary["in_range_share"] <= 1.0
    assert 0.0 < summary["delta_rho_min"] <= summary["delta_rho_at_centre"] <= summary["delta_rho_max"]
    # δρ at the centre (home) is the CLI's: pkm jacobian --json prints it as error_amplification.
    machine = pkm.Machine.load(summary["machine"])
    home = np.asarray(machine.home, dtype=float)
    home = ",".join(repr(float(v)) for v in np.concatenate([home[:3], np.degrees(home[3:])]))  # the CLI's degrees
    cli = subprocess.run([os.environ["PKM_BINARY"], "jacobian", "--machine", summary["machine"], "--pose", home,
                          "--json"], capture_output=True, text=True, check=True)
    assert summary["delta_rho_at_centre"] == pytest.approx(json.loads(cli.stdout)["error_amplification"], rel=1e-12)


def test_layout_sweep_finds_an_interior_optimum(tmp_path):
    summary, _ = run_example("layout_sweep", tmp_path, "--workers", "2")
    ratios = summary["ratios"]
    for separation, best in summary["best_ratio"].items():
        worst = summary["worst_delta_rho"][separation]
        assert ratios[0] < best < ratios[-1], (separation, worst)
        assert np.isfinite(summary["best_worst_delta_rho"][separation])
        assert summary["best_worst_delta_rho"][separation] == min(worst)
