"""Errors of pkm.Machine and the batch calls: typed exceptions with file, line, column and key as the CLI reports
them; arguments of the wrong shape or dtype refused with clear messages; NaN refused with the row."""

from __future__ import annotations

import re

import numpy as np
import pytest

import pkm
from pkm._machine_text import machine_json_text
from kinematics_helpers import HEXAPOD_CH5, run_cli

CLI_LOCATION = re.compile(r"error: (?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?P<key>[^:]+): ")

# (what to replace in hexapod_ch5.yaml, with what): each makes one entry invalid.
MALFORMED = {
    "list_for_number": ("actuator_min: 350 ", "actuator_min: [350] "),
    "unknown_key": ("tool: [0, 0, 150]", "tool: [0, 0, 150]\ntooll: 3"),
    "short_point": ("  - [-400.0, 0.0, 0.0]", "  - [-400.0, 0.0]"),
    "bad_angles": ("angles: krylov", "angles: kyrlov"),
}


@pytest.fixture(scope="module")
def hexapod():
    return pkm.Machine.load(HEXAPOD_CH5)


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_malformed_file_locates_the_error_as_the_cli_does(tmp_path, case):
    old, new = MALFORMED[case]
    text = HEXAPOD_CH5.read_text()
    assert old in text
    path = tmp_path / f"{case}.yaml"
    path.write_text(text.replace(old, new, 1))
    cli = run_cli("ik", "--machine", str(path), "--pose", "0,0,700,0,0,0", check=False)
    assert cli.returncode != 0
    where = CLI_LOCATION.search(cli.stderr)
    assert where, cli.stderr
    with pytest.raises(pkm.MachineFileError) as raised:
        pkm.Machine.load(path)
    e = raised.value
    assert (e.file, e.line, e.column, e.key) == (where["file"], int(where["line"]), int(where["column"]), where["key"])
    assert e.code == "bad_input" and isinstance(e, ValueError)
    assert str(e) in cli.stderr  # the same one-line message
    # The same text from a string: the same place, under the source name given.
    with pytest.raises(pkm.MachineFileError) as from_text:
        pkm.Machine.from_yaml(path.read_text(), source="inline")
    assert (from_text.value.file, from_text.value.line, from_text.value.key) == ("inline", e.line, e.key)


def test_yaml_syntax_error_is_a_machine_file_error(tmp_path):
    path = tmp_path / "broken.yaml"
    path.write_text("type: hexapod\nbase_joints: [[1, 2, 3]\n")
    with pytest.raises(pkm.MachineFileError) as raised:
        pkm.Machine.load(path)
    assert raised.value.file == str(path) and raised.value.line is not None


def test_missing_file_is_a_file_error(tmp_path):
    with pytest.raises(pkm.FileIOError):
        pkm.Machine.load(tmp_path / "absent.yaml")
    with pytest.raises(pkm.FileIOError):
        pkm.read_machine_dict(tmp_path / "absent.yaml")


def test_from_dict_names_the_key_and_its_line_in_the_json_text():
    d = pkm.read_machine_dict(HEXAPOD_CH5)
    d["limits"]["actuator_min"] = "short"
    with pytest.raises(pkm.MachineFileError) as raised:
        pkm.Machine.from_dict(d)
    e = raised.value
    assert e.key == "limits.actuator_min" and e.file == "<dict>"
    line = machine_json_text(d).splitlines()[e.line - 1]
    assert '"actuator_min"' in line and line[e.column - 1:].startswith('"short"')


@pytest.mark.parametrize("value, key", [(float("nan"), "limits.actuator_max"), (object(), "limits.actuator_max"),
                                        ({1: 2}, "limits.actuator_max.1")])
def test_from_dict_refuses_values_json_cannot_hold(value, key):
    d = pkm.read_machine_dict(HEXAPOD_CH5)
    d["limits"]["actuator_max"] = value
    with pytest.raises(pkm.MachineFileError) as raised:
        pkm.Machine.from_dict(d)
    assert raised.value.key == key


def test_from_dict_needs_a_dict():
    with pytest.raises(TypeError):
        pkm.Machine.from_dict([1, 2, 3])


def test_unreachable_pose_raises_with_the_row(hexapod):
    poses = np.tile(hexapod.home, (4, 1))
    poses[2, 2] = 3000.0
    with pytest.raises(pkm.UnreachableError) as raised:
        hexapod.ik(poses)
    assert raised.value.row == 2 and str(raised.value).startswith("poses[2]: ")
    assert "actuator_max" in str(raised.value)  # the range check's words, as `pkm ik` says them
    with pytest.raises(pkm.UnreachableError) as single:
        hexapod.ik(poses[2])
    assert single.value.row is None


@pytest.mark.parametrize("shape, shown", [((3, 5), "(3, 5)"), ((6, 3), "(6, 3)"), ((2, 6, 1), "(2, 6, 1)"),
                                          ((), "()"), ((5,), "(5,)"), ((0,), "(0,)")])
def test_wrong_shapes_are_refused(hexapod, shape, shown):
    with pytest.raises(ValueError) as raised:
        hexapod.ik(np.zeros(shape))
    assert str(raised.value) == f"poses must have shape (N, 6) or (6,), got {shown}"


def test_actuator_shapes_name_the_actuator_count(hexapod):
    with pytest.raises(ValueError, match=r"actuators must have shape \(N, 6\) or \(6,\), got \(2, 3\)"):
        hexapod.fk(np.zeros((2, 3)))
    with pytest.raises(ValueError, match="one row"):
        hexapod.fk_all(np.full((2, 6), 600.0))


@pytest.mark.parametrize("bad", [np.zeros((2, 6), complex), np.zeros((2, 6), object), np.zeros((2, 6), bool),
                                 np.array([["1"] * 6]), [["a"] * 6], np.zeros((2, 6), np.longdouble)],
                         ids=["complex", "object", "bool", "str_array", "str_list", "longdouble"])
def test_wrong_dtypes_are_refused(hexapod, bad):
    if isinstance(bad, np.ndarray) and bad.dtype == np.longdouble and np.finfo(np.longdouble).bits == 64:
        pytest.skip("longdouble is float64 here")
    with pytest.raises(TypeError, match="poses"):
        hexapod.ik(bad)


def test_lossless_conversions_are_accepted(hexapod):
    home = hexapod.home
    expected = hexapod.ik(np.array([home, home]))
    assert np.array_equal(hexapod.ik([list(home), tuple(home)]), expected)
    assert np.array_equal(hexapod.ik(np.array([home, home], dtype=">f8")), expected)  # big-endian
    assert np.array_equal(hexapod.ik(np.asfortranarray([home, home])), expected)
    assert np.array_equal(hexapod.ik(np.array([home, home, home])[::2]), expected)  # strided
    integers = np.array([[0, 0, 700, 0, 0, 0]], dtype=np.int32)
    assert np.array_equal(hexapod.ik(integers), hexapod.ik(integers.astype(float)))
    f32 = np.array([[1.5, -2.25, 700.125, 0.0, 0.0625, 0.0]], dtype=np.float32)
    assert np.array_equal(hexapod.ik(f32), hexapod.ik(f32.astype(np.float64)))


def test_ragged_lists_are_refused(hexapod):
    with pytest.raises(ValueError, match="poses"):
        hexapod.ik([[0, 0, 700, 0, 0, 0], [0, 0, 700]])


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_values_are_refused_with_the_row(hexapod, bad):
    poses = np.tile(hexapod.home, (5, 1))
    poses[3, 4] = bad
    for call in (hexapod.ik, hexapod.jacobian, hexapod.conditioning):
        with pytest.raises(ValueError, match=r"poses\[3\] contains NaN or infinity"):
            call(poses)
    with pytest.raises(ValueError, match=r"poses\[3\]"):
        hexapod.ik(poses, errors="nan")  # bad input is not an unreachable pose
    q = np.full((4, 6), 603.0)
    q[1, 0] = bad
    for warm in (True, False):
        with pytest.raises(ValueError, match=r"actuators\[1\] contains NaN"):
            hexapod.fk(q, warm=warm)


def test_errors_argument_is_checked(hexapod):
    with pytest.raises(ValueError, match="errors must be 'raise' or 'nan'"):
        hexapod.ik(hexapod.home, errors="ignore")


def test_fk_all_of_a_carriage_machine_and_guess_checked(hexapod):
    hexaglide = pkm.Machine.load(HEXAPOD_CH5.parent / "hexaglide.yaml")  # its carriages' Gough-Stewart platform
    modes = hexaglide.fk_all(hexaglide.ik(hexaglide.home))
    assert len(modes) >= 2
    assert modes[0]["branch"] == 0 and np.allclose(modes[0]["pose"][:3], np.asarray(hexaglide.home)[:3], atol=1e-6)
    genhexkins = pkm.Machine.load(HEXAPOD_CH5.parent / "hexapod_genhexkins.yaml")  # every hexapod enumerates
    assert len(genhexkins.fk_all(genhexkins.ik(genhexkins.home))) >= 2
    with pytest.raises(ValueError, match="guess"):
        hexapod.fk(hexapod.ik(hexapod.home), guess=np.zeros(5))


def test_out_argument_is_checked(hexapod):
    poses = np.tile(hexapod.home, (3, 1))
    out = np.empty((3, 6))
    assert hexapod.ik(poses, out=out) is out and np.array_equal(out, hexapod.ik(poses))
    with pytest.raises(ValueError, match=r"out must have shape \(3, 6\), got \(3, 5\)"):
        hexapod.ik(poses, out=np.empty((3, 5)))
    for bad in (np.empty((3, 6), np.float32), np.empty((6, 3)).T, [[0.0] * 6] * 3):
        with pytest.raises(TypeError, match="out must be a writeable C-contiguous float64 array"):
            hexapod.ik(poses, out=bad)
    with pytest.raises(ValueError, match="share memory"):
        hexapod.ik(poses, out=poses)


def test_a_misspelt_keyword_is_named_in_one_line(hexapod):
    # pybind11 alone would print every overload's signature; pkm names the keyword and the nearest accepted one.
    cases = [(lambda: hexapod.ik(hexapod.home, error="nan"), "ik() got an unexpected keyword argument 'error'; "
              "did you mean 'errors'?"),
             (lambda: pkm.interpret("x.ngc", subroutine_paht="."), "did you mean 'subroutine_path'?"),
             (lambda: pkm.Machine.load(paht="x.yaml"), "load() got an unexpected keyword argument 'paht'")]
    for call, expected in cases:
        with pytest.raises(TypeError) as caught:
            call()
        message = str(caught.value)
        assert expected in message and "\n" not in message, message
    # Right keywords still pass through, and the version is the command's.
    assert hexapod.ik(hexapod.home, errors="nan").shape == (6,)
    assert pkm.__version__.count(".") == 2


def test_poses_can_be_given_and_returned_in_degrees(hexapod):
    in_degrees = np.array([[-20.0, 10.0, 700.0, 5.0, -3.0, 10.0], [10.0, -5.0, 690.0, -4.0, 2.0, -8.0]])
    in_radians = in_degrees.copy()
    in_radians[:, 3:] = np.radians(in_radians[:, 3:])
    actuators = hexapod.ik(in_radians)
    np.testing.assert_array_equal(hexapod.ik(in_degrees, angles="deg"), actuators)
    np.testing.assert_allclose(hexapod.fk(actuators, angles="deg"), in_degrees, atol=1e-9)
    poses, _ = hexapod.fk(actuators, info=True, angles="deg")
    np.testing.assert_allclose(poses, in_degrees, atol=1e-9)
    np.testing.assert_allclose(hexapod.jacobian(in_degrees, angles="deg"), hexapod.jacobian(in_radians))
    np.testing.assert_allclose(pkm.modes(hexapod, in_degrees[0], angles="deg")["frequencies_Hz"],
                               pkm.modes(hexapod, in_radians[0])["frequencies_Hz"])
    np.testing.assert_allclose(hexapod.pose_from_abc(hexapod.abc_from_pose(in_degrees, angles="deg"), angles="deg"),
                               in_degrees, atol=1e-9)
    with pytest.raises(ValueError, match="'rad' or 'deg'"):
        hexapod.ik(in_degrees, angles="degrees")
    with pytest.raises(TypeError, match="did you mean 'angles'"):
        hexapod.ik(in_degrees, angle="deg")
