"""pkm.Machine: loading from a file, YAML text and a dict; read_machine_dict; the properties; pickling."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

import pkm
from kinematics_helpers import HEXAPOD_CH5, MACHINE_FILES, poses_near_home, rad_from_deg

MACHINE_IDS = [f.stem for f in MACHINE_FILES]


@pytest.mark.parametrize("machine_file", MACHINE_FILES, ids=MACHINE_IDS)
def test_dict_and_text_round_trips_give_identical_ik(machine_file):
    loaded = pkm.Machine.load(machine_file)
    poses = poses_near_home(loaded, 8, seed=11)
    expected = loaded.ik(poses)
    from_dict = pkm.Machine.from_dict(pkm.read_machine_dict(machine_file))
    from_text = pkm.Machine.from_yaml(machine_file.read_text(), source=str(machine_file))
    for other in (from_dict, from_text):
        assert np.array_equal(other.ik(poses), expected)
        assert np.array_equal(other.home, loaded.home)
        assert other.actuator_limits == loaded.actuator_limits
    assert from_dict.source == "<dict>" and from_text.source == str(machine_file)


@pytest.mark.parametrize("machine_file", MACHINE_FILES, ids=MACHINE_IDS)
def test_properties_match_the_file(machine_file):
    machine = pkm.Machine.load(machine_file)
    d = pkm.read_machine_dict(machine_file)
    assert machine.type == d["type"]
    assert machine.name == d.get("name", d["type"])
    assert machine.source == str(machine_file)
    assert machine.angle_convention == d.get("angles", "abc")
    assert len(machine.controlled_axes) == 6 and all(isinstance(c, bool) for c in machine.controlled_axes)
    assert machine.actuator_count == machine.ik(machine.home).shape[0]
    assert machine.actuator_unit in ("mm", "rad")
    tool = d.get("tool", [0, 0, 0])
    assert machine.tool_mm.tolist() == [*map(float, tool), 0.0][:3]
    # The file's home (mm, degrees) in the controlled coordinates; the others are computed.
    if "home" in d and len(d["home"]) == 6:
        home_file = np.array([v if i < 3 else rad_from_deg(v) for i, v in enumerate(d["home"])])
        controlled = np.array(machine.controlled_axes)
        np.testing.assert_allclose(machine.home[controlled], home_file[controlled], rtol=0, atol=1e-12)
    limits = d.get("limits", {})
    to_internal = rad_from_deg if machine.actuator_unit == "rad" else float
    for key, name in (("actuator_min", "min"), ("actuator_max", "max"), ("actuator_speed", "speed")):
        expected = to_internal(limits[key]) if key in limits else None
        assert machine.actuator_limits[name] == pytest.approx(expected, rel=1e-15), key
    assert set(machine.actuator_limits) == {"min", "max", "speed", "accel", "force_N"}
    assert machine.name in repr(machine) and machine.type in repr(machine)


def test_read_machine_dict_types_scalars_as_yaml_does(tmp_path):
    d = pkm.read_machine_dict(HEXAPOD_CH5)
    assert d["limits"]["actuator_min"] == 350 and type(d["limits"]["actuator_min"]) is int
    assert type(d["base_joints"][0][0]) is float and d["base_joints"][1][1] == 346.41016151377545
    assert d["motion"]["program_origin_mm"] == [0, 0, 700]
    assert list(d)[:3] == ["name", "type", "angles"]  # file order
    text = tmp_path / "scalars.yaml"
    text.write_text("a: ~\nb: true\nc: 'true'\nd: 0x1F\ne: 1e3\nf: -.inf\ng: .5\nh: word\ni: \"12\"\nj: 007\n")
    s = pkm.read_machine_dict(text)
    assert s == {"a": None, "b": True, "c": "true", "d": 31, "e": 1000.0, "f": float("-inf"), "g": 0.5,
                 "h": "word", "i": "12", "j": 7}
    assert type(s["e"]) is float and type(s["d"]) is int


def test_from_dict_accepts_numpy_values_and_overrides():
    d = pkm.read_machine_dict(HEXAPOD_CH5)
    d["base_joints"] = np.array(d["base_joints"]) * 1.1  # a wider base, as an array
    d["limits"]["actuator_max"] = np.float32(1000)
    d["limits"]["actuator_min"] = np.int64(300)
    wider = pkm.Machine.from_dict(d, source="wider base")
    assert wider.source == "wider base"
    assert wider.actuator_limits["max"] == 1000.0 and wider.actuator_limits["min"] == 300.0
    original = pkm.Machine.load(HEXAPOD_CH5)
    assert not np.allclose(wider.ik(original.home), original.ik(original.home))


def test_pickle_and_deepcopy_keep_the_machine():
    machine = pkm.Machine.load(HEXAPOD_CH5)
    poses = poses_near_home(machine, 5, seed=12)
    for clone in (pickle.loads(pickle.dumps(machine)), copy.deepcopy(machine)):
        assert clone is not machine
        assert clone.source == machine.source and clone.name == machine.name
        assert np.array_equal(clone.ik(poses), machine.ik(poses))
        assert np.array_equal(clone.tool_mm, machine.tool_mm)


def test_help_states_units_and_conventions():
    doc = pkm.Machine.ik.__doc__
    for words in ("poses", "mm", "rad", "angle_convention", "errors", "check_limits", "UnreachableError"):
        assert words in doc, words
    assert "guess" in pkm.Machine.fk.__doc__ and "warm" in pkm.Machine.fk.__doc__
    assert "delta_rho" in pkm.Machine.conditioning.__doc__
