"""pkm.layouts: the shipped example machines reproduced from their parameters, to the last bit, and the layout's
geometry (radii, separations) as documented."""

import math
import os
from pathlib import Path

import numpy as np
import pytest

import pkm
from pkm import layouts

MACHINES = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2])) / "examples/machines"

CASES = [
    ("hexapod_ch3.yaml", lambda: layouts.hexapod(500, 300), ("base_joints", "platform_joints")),
    ("hexapod_ch3_delta30.yaml", lambda: layouts.hexapod(500, 300, platform_separation_deg=30),
     ("base_joints", "platform_joints")),
    ("hexapod_ch5.yaml", lambda: layouts.hexapod(400, 200, height_mm=550, tool_mm=150),
     ("base_joints", "platform_joints")),
    ("tripod.yaml", lambda: layouts.tripod(400, 200), ("base_joints", "base_axes", "platform_joints")),
]


@pytest.mark.parametrize("file, make, joint_keys", CASES, ids=[case[0] for case in CASES])
def test_the_example_files_are_reproduced(file, make, joint_keys):
    shipped = pkm.read_machine_dict(str(MACHINES / file))
    made = make()
    for key in joint_keys + ("type", "angles"):
        assert made[key] == shipped[key], key  # exact: the files' numbers to the last bit
    assert [float(v) for v in shipped["tool"]] == made["tool"]
    assert [float(v) for v in shipped["home"]] == made["home"]

    # The dict is a machine: the same strut lengths as the file's machine over a few poses.
    from_file = pkm.Machine.load(str(MACHINES / file))
    from_layout = pkm.Machine.from_dict(made)
    rng = np.random.default_rng(1)
    poses = np.tile(np.asarray(from_file.home, dtype=float), (5, 1))
    poses[:, :3] += rng.uniform(-20.0, 20.0, size=(5, 3))
    poses[:, 3:] += rng.uniform(-0.05, 0.05, size=(5, 3))
    if from_file.type == "tripod":  # x, y and C follow from z, A and B: level poses at several heights
        poses = np.tile(np.asarray(from_file.home, dtype=float), (5, 1))
        poses[:, 2] += np.linspace(-40.0, 40.0, 5)
    assert np.array_equal(from_layout.ik(poses), from_file.ik(poses))


def _angle_deg(point):
    return math.degrees(math.atan2(point[1], point[0]))


def _gap_deg(a, b):
    return abs((_angle_deg(b) - _angle_deg(a) + 180.0) % 360.0 - 180.0)


@pytest.mark.parametrize("base_sep, platform_sep", [(60.0, 0.0), (20.0, 35.0), (0.0, 90.0), (120.0, 120.0)])
def test_hexapod_joints_lie_on_their_circles_with_the_separations_asked_for(base_sep, platform_sep):
    machine = layouts.hexapod(450.0, 250.0, base_separation_deg=base_sep, platform_separation_deg=platform_sep,
                              height_mm=600.0, tool_mm=[10.0, 0.0, 120.0], pair_angle_deg=10.0)
    base, platform = np.array(machine["base_joints"]), np.array(machine["platform_joints"])
    assert np.allclose(np.linalg.norm(base[:, :2], axis=1), 450.0) and not base[:, 2].any()
    assert np.allclose(np.linalg.norm(platform[:, :2], axis=1), 250.0) and not platform[:, 2].any()
    for k in range(3):
        # The platform joints of a strut pair δ apart, centred on the pair's angle; the base joints of adjacent
        # pairs base_separation_deg apart.
        assert _gap_deg(platform[2 * k], platform[2 * k + 1]) == pytest.approx(platform_sep, abs=1e-9)
        middle = (platform[2 * k] + platform[2 * k + 1]) / 2.0
        assert _angle_deg(middle) == pytest.approx((10.0 + 120.0 * k + 180.0) % 360.0 - 180.0, abs=1e-9)
        assert _gap_deg(base[2 * k + 1], base[(2 * k + 2) % 6]) == pytest.approx(base_sep, abs=1e-9)
        assert _gap_deg(base[2 * k], base[2 * k + 1]) == pytest.approx(120.0 - base_sep, abs=1e-9)
    assert machine["tool"] == [10.0, 0.0, 120.0]
    assert machine["home"] == [10.0, 0.0, 720.0, 0.0, 0.0, 0.0]


def test_sections_pass_through_and_a_built_layout_loads():
    made = layouts.hexapod(400, 200, height_mm=550, tool_mm=150, limits={"actuator_min": 350, "actuator_max": 900},
                           motion={"max_feed_mm_min": 3000}, drives={"step_mm": 0.001}, name="study")
    assert made["limits"] == {"actuator_min": 350, "actuator_max": 900} and made["drives"] == {"step_mm": 0.001}
    machine = pkm.Machine.from_dict(made)
    assert machine.name == "study" and machine.actuator_count == 6
    assert machine.actuator_limits["max"] == 900


@pytest.mark.parametrize("kwargs, match", [
    ({"base_radius_mm": -1.0}, "base_radius_mm must be a positive"),
    ({"platform_radius_mm": float("nan")}, "platform_radius_mm must be a positive"),
    ({"platform_separation_deg": 130.0}, r"platform_separation_deg must be an angle in \[0, 120\]"),
    ({"base_separation_deg": -5.0}, "base_separation_deg must be an angle"),
    ({"tool_mm": [0, 0]}, "tool_mm must be a distance"),
    ({"height_mm": 0.0}, "height_mm must be a positive"),
    ({"base_joints": [[0, 0, 0]] * 6}, "'base_joints' is computed"),
])
def test_bad_parameters_raise_value_errors(kwargs, match):
    arguments = {"base_radius_mm": 500.0, "platform_radius_mm": 300.0, **kwargs}
    with pytest.raises(ValueError, match=match):
        layouts.hexapod(**arguments)
