"""Shared by the kinematics tests: the shipped machines, the CLI, and poses in user units (mm, degrees) whose
radian values are computed exactly as the CLI computes them (core/units.hpp), so that Python and the CLI see
the same doubles."""

from __future__ import annotations

import json
import math
import os
import subprocess
from pathlib import Path

import numpy as np

import pkm

SOURCE_DIR = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PKM_BINARY = os.environ.get("PKM_BINARY", "pkm")
MACHINE_FILES = sorted((SOURCE_DIR / "examples" / "machines").glob("*.yaml"))
HEXAPOD_CH5 = SOURCE_DIR / "examples" / "machines" / "hexapod_ch5.yaml"


def rad_from_deg(deg: float) -> float:
    return deg * (math.pi / 180.0)  # as core/units.hpp: angle_deg * (kPi / 180.0)


def deg_from_rad(rad: float) -> float:
    return rad * (180.0 / math.pi)


def run_cli(*args: str, check: bool = True) -> subprocess.CompletedProcess:
    result = subprocess.run([PKM_BINARY, *args], capture_output=True, text=True, timeout=60)
    if check and result.returncode != 0:
        raise AssertionError(f"pkm {' '.join(args)} failed ({result.returncode}): {result.stderr}")
    return result


def cli_json(*args: str) -> dict:
    return json.loads(run_cli(*args, "--json").stdout)


def user_indices(machine: pkm.Machine) -> list[int]:
    """The pose coordinates the CLI takes and prints: all six, or for planar machines the controlled ones."""
    if machine.is_planar:
        return [i for i, c in enumerate(machine.controlled_axes) if c]
    return list(range(6))


def user_text(values) -> str:
    return ",".join(repr(float(v)) for v in values)


def pose_from_user(values_user) -> np.ndarray:
    """A (6,) pose in rad from mm and degrees."""
    return np.array([v if i < 3 else rad_from_deg(v) for i, v in enumerate(values_user)])


def user_poses_near_home(machine: pkm.Machine, count: int, seed: int, range_mm: float = 5.0,
                         range_deg: float = 2.0) -> np.ndarray:
    """`count` reachable poses (in mm and degrees, shape (count, 6)) around home, moving only the controlled
    coordinates, rounded to 1e-6 so that they print short."""
    rng = np.random.default_rng(seed)
    home_user = np.array([v if i < 3 else deg_from_rad(v) for i, v in enumerate(machine.home)])
    controlled = np.array(machine.controlled_axes)
    out = [np.round(home_user, 9)]
    while len(out) < count:
        step = rng.uniform(-1, 1, 6) * np.where(np.arange(6) < 3, range_mm, range_deg) * controlled
        candidate = np.round(home_user + step, 6)
        if not np.isnan(machine.ik(pose_from_user(candidate), errors="nan")).any():
            out.append(candidate)
    return np.array(out)


def poses_near_home(machine: pkm.Machine, count: int, seed: int, range_mm: float = 5.0,
                    range_deg: float = 2.0) -> np.ndarray:
    """Reachable poses in rad around home, shape (count, 6)."""
    return np.array([pose_from_user(p) for p in user_poses_near_home(machine, count, seed, range_mm, range_deg)])


def assert_close(actual, expected, rel: float = 1e-12, what: str = "") -> None:
    actual = np.asarray(actual, dtype=float)
    expected = np.asarray(expected, dtype=float)
    assert actual.shape == expected.shape, f"{what}: shape {actual.shape} != {expected.shape}"
    scale = np.maximum(1.0, np.abs(expected))
    worst = np.max(np.abs(actual - expected) / scale) if actual.size else 0.0
    assert worst <= rel, f"{what}: differs by {worst:.3g} (relative), {actual} vs {expected}"
