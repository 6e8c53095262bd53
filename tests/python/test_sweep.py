"""pkm.sweep: the design space's order, the variants' overrides, identical tables on every executor (serial, local
processes, a 2-worker Dask LocalCluster started here), failing points, and clear errors for bad specs."""

import functools
import os
from pathlib import Path

import numpy as np
import pytest

import pkm
from pkm import layouts

SOURCE = Path(os.environ.get("PKM_SOURCE_DIR", Path(__file__).resolve().parents[2]))
CH5 = str(SOURCE / "examples/machines/hexapod_ch5.yaml")


# ---- evaluate functions: module level, so that worker processes can import them -----------------------------------

def add_and_label(machine, params):
    assert machine is None
    return {"sum": params["a"] + 10 * params["b"], "label": f"{params['a']}-{params['b']}"}


def home_struts(machine, params):
    """Strut lengths at home shifted by the point's x, the actuator limits, and the condition number there."""
    pose = np.array(machine.home, dtype=float)
    pose[0] += params.get("x_mm", 0.0)
    lengths = machine.ik(pose[np.newaxis, :])[0]
    result = {"l0_mm": float(lengths[0]), "l5_mm": float(lengths[5]), "machine_name": machine.name,
              "actuator_max_mm": float(machine.actuator_limits["max"] or np.nan)}
    return result


def conditioning_or_fail(machine, params):
    """Fails at x > 40 mm (a ZeroDivisionError), otherwise the strut lengths and δρ at the shifted pose."""
    if params["x_mm"] > 40.0:
        raise ZeroDivisionError(f"no luck at x = {params['x_mm']:.3f}")
    pose = np.array(machine.home, dtype=float)
    pose[0] += params["x_mm"]
    pose[5] += np.radians(params["c_deg"])
    lengths = machine.ik(pose[np.newaxis, :])[0]
    measures = machine.conditioning(pose[np.newaxis, :])
    return {"sum_mm": float(lengths.sum()), "delta_rho": float(measures["delta_rho"][0])}


def scalar_only(machine, params):
    return params["k"] * 0.5


def keys_by_parity(machine, params):
    k = params["k"]
    return {"half": k / 2} if k % 2 == 0 else {"flag": True, "half": k / 2, "odd": k}


def wrong_result(machine, params):
    return {"lengths": np.zeros(3)}


# ---- the design space ----------------------------------------------------------------------------------------------

def test_grid_is_the_product_with_the_last_name_fastest():
    names, points = pkm.design_points({"a": [1, 2], "b": np.array([5, 6, 7])})
    assert names == ["a", "b"]
    assert points == [(1, 5), (1, 6), (1, 7), (2, 5), (2, 6), (2, 7)]
    assert all(type(v) is int for point in points for v in point)  # numpy scalars become plain numbers

    table = pkm.sweep(add_and_label, {"a": [1, 2], "b": [5, 6, 7]}, executor="serial", table="numpy")
    assert table.dtype.names == ("a", "b", "sum", "label")
    assert table["a"].tolist() == [1, 1, 1, 2, 2, 2]
    assert table["b"].tolist() == [5, 6, 7, 5, 6, 7]
    assert table["sum"].tolist() == [51, 61, 71, 52, 62, 72]
    assert table["label"].tolist() == ["1-5", "1-6", "1-7", "2-5", "2-6", "2-7"]


def test_random_points_are_uniform_in_range_and_fixed_by_the_seed():
    space = {"x_mm": (-5.0, 5.0), "c_deg": [10, 20]}
    names, first = pkm.design_points(space, "random", samples=200, seed=7)
    _, again = pkm.design_points(space, "random", samples=200, seed=7)
    _, other = pkm.design_points(space, "random", samples=200, seed=8)
    assert names == ["x_mm", "c_deg"] and len(first) == 200
    assert first == again and first != other
    drawn = np.array(first)
    assert (drawn[:, 0] >= -5).all() and (drawn[:, 0] < 5).all() and (drawn[:, 1] >= 10).all()
    assert drawn[:, 0].min() < -4 and drawn[:, 0].max() > 4  # spread over the range, not a constant
    # The documented draw: one (samples, names) matrix from numpy's default_rng(seed).
    expected = np.random.default_rng(7).uniform([-5.0, 10.0], [5.0, 20.0], size=(200, 2))
    assert np.array_equal(drawn, expected)


def test_a_scalar_result_is_the_value_column_and_chunks_do_not_change_the_table():
    space = {"k": list(range(23))}
    one = pkm.sweep(scalar_only, space, executor="serial", chunk_size=1, table="numpy")
    big = pkm.sweep(scalar_only, space, executor="serial", chunk_size=100, table="numpy")
    assert one.dtype.names == ("k", "value")
    assert np.array_equal(one, big)
    assert one["value"].tolist() == [0.5 * k for k in range(23)]


def test_results_missing_from_some_rows_are_nan_whatever_the_chunks():
    tables = [pkm.sweep(keys_by_parity, {"k": list(range(11))}, executor="serial", chunk_size=size, table="numpy")
              for size in (1, 2, 100)]
    assert tables[0].dtype.names == ("k", "half", "flag", "odd")  # in the order first returned
    assert tables[0]["half"].tolist() == [k / 2 for k in range(11)]
    assert np.isnan(tables[0]["odd"][0::2]).all() and tables[0]["odd"][1::2].tolist() == [1, 3, 5, 7, 9]
    assert np.isnan(tables[0]["flag"][0::2]).all() and (tables[0]["flag"][1::2] == 1.0).all()
    for other in tables[1:]:
        assert other.dtype == tables[0].dtype
        assert all(np.array_equal(other[n], tables[0][n], equal_nan=True) for n in other.dtype.names)


# ---- variants -----------------------------------------------------------------------------------------------------

def test_overrides_reach_the_machine_and_other_names_only_evaluate():
    space = {"base_joints[0][0]": [400.0, 420.0], "limits.actuator_max": [900.0, 950.0], "name": ["variant"],
             "x_mm": [0.0, 3.0]}
    table = pkm.sweep(home_struts, space, base=CH5, executor="serial", table="numpy")
    assert len(table) == 8
    assert set(table["machine_name"]) == {"variant"}
    assert np.array_equal(table["actuator_max_mm"], table["limits.actuator_max"])
    reference = pkm.read_machine_dict(CH5)
    for row in table:
        variant = pkm.read_machine_dict(CH5)
        variant["base_joints"][0][0] = float(row["base_joints[0][0]"])
        machine = pkm.Machine.from_dict(variant)
        pose = np.array(machine.home, dtype=float)
        pose[0] += row["x_mm"]
        lengths = machine.ik(pose[np.newaxis, :])[0]
        assert row["l0_mm"] == lengths[0] and row["l5_mm"] == lengths[5]
    # The joint moved 20 mm outwards lengthens strut 0 and leaves strut 5 alone; x only moves the pose.
    assert table["l0_mm"][4] > table["l0_mm"][0] and table["l5_mm"][4] == table["l5_mm"][0]
    assert table["l0_mm"][1] != table["l0_mm"][0]
    assert reference["base_joints"][0][0] == 400.0  # the base itself is not changed


def test_a_layout_function_builds_the_variants():
    base = functools.partial(layouts.hexapod, 500, 300)
    table = pkm.sweep(home_struts, {"platform_separation_deg": [0.0, 30.0]}, base=base, executor="serial",
                      table="numpy")
    for separation, file in ((0.0, "hexapod_ch3.yaml"), (30.0, "hexapod_ch3_delta30.yaml")):
        machine = pkm.Machine.load(str(SOURCE / "examples/machines" / file))
        lengths = machine.ik(np.array(machine.home, dtype=float)[np.newaxis, :])[0]
        row = table[table["platform_separation_deg"] == separation][0]
        assert row["l0_mm"] == lengths[0] and row["l5_mm"] == lengths[5]


# ---- executors ----------------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def dask_cluster():
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    yield cluster
    cluster.close()


@pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")  # tornado, inside distributed
def test_serial_processes_and_dask_give_the_same_table(dask_cluster):
    space = {"x_mm": (-20.0, 60.0), "c_deg": (-5.0, 5.0)}
    common = dict(base=CH5, method="random", samples=64, seed=3, on_error="nan", table="numpy")
    serial = pkm.sweep(conditioning_or_fail, space, executor="serial", **common)
    processes = pkm.sweep(conditioning_or_fail, space, executor="processes", workers=2, chunk_size=5, **common)
    dask = pkm.sweep(conditioning_or_fail, space, executor="dask", scheduler=dask_cluster.scheduler_address,
                     chunk_size=7, **common)
    failed = serial["x_mm"] > 40.0
    assert 0 < failed.sum() < len(serial)  # both kinds of row are compared
    assert np.isfinite(serial["delta_rho"][~failed]).all() and (serial["delta_rho"][~failed] > 0).all()
    for other in (processes, dask):
        assert other.dtype == serial.dtype
        for name in serial.dtype.names:
            if serial.dtype[name].kind == "f":
                assert np.array_equal(other[name], serial[name], equal_nan=True), name
            else:
                assert other[name].tolist() == serial[name].tolist(), name


def test_dask_without_a_scheduler_says_what_it_needs():
    distributed = pytest.importorskip("distributed")
    try:
        distributed.default_client()
        pytest.skip("a Dask client is active in this process")
    except ValueError:
        pass
    with pytest.raises(ValueError, match="scheduler="):
        pkm.sweep(scalar_only, {"k": [1]}, executor="dask")


def test_a_lambda_cannot_go_to_processes():
    with pytest.raises(TypeError, match="module level"):
        pkm.sweep(lambda machine, params: 1.0, {"k": [1, 2]}, executor="processes", workers=1)


# ---- failing points -----------------------------------------------------------------------------------------------

def test_a_failing_point_raises_or_becomes_a_nan_row():
    space = {"x_mm": [0.0, 50.0, 10.0, 45.0], "c_deg": [0.0]}
    with pytest.raises(ZeroDivisionError, match="x = 50.000") as raised:
        pkm.sweep(conditioning_or_fail, space, base=CH5, executor="serial")
    assert any("point 1" in note for note in raised.value.__notes__)  # the first failing point, by order
    table = pkm.sweep(conditioning_or_fail, space, base=CH5, executor="serial", on_error="nan", table="numpy")
    assert table["error"].tolist()[0] == "" and table["error"].tolist()[2] == ""
    assert table["error"][1] == "ZeroDivisionError: no luck at x = 50.000"
    assert np.isnan(table["sum_mm"][[1, 3]]).all() and np.isfinite(table["sum_mm"][[0, 2]]).all()


def test_a_variant_that_does_not_load_is_a_failing_point():
    # Struts of at most 500 mm cannot reach the ch5 home (struts of about 600 mm): the machine does not load.
    table = pkm.sweep(home_struts, {"limits.actuator_max": [900.0, 500.0]}, base=CH5, executor="serial",
                      on_error="nan", table="numpy")
    assert table["error"][0] == "" and np.isfinite(table["l0_mm"][0])
    assert table["error"][1].startswith(("LimitExceededError", "MachineFileError", "InputError"))
    assert np.isnan(table["l0_mm"][1])
    with pytest.raises(pkm.Error):
        pkm.sweep(home_struts, {"limits.actuator_max": [500.0]}, base=CH5, executor="serial")


def test_a_result_that_is_not_a_scalar_is_refused():
    with pytest.raises(TypeError, match="'lengths' is a ndarray of shape"):
        pkm.sweep(wrong_result, {"k": [1]}, executor="serial")


# ---- bad specs ----------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("space, kwargs, error, match", [
    ([1, 2], {}, TypeError, "must be a dict"),
    ({}, {}, ValueError, "space is empty"),
    ({"a": "abc"}, {}, TypeError, r"space\['a'\] must be a list"),
    ({"a": 3.0}, {}, TypeError, r"a single value: \[3.0\]"),
    ({"a": []}, {}, ValueError, "has no values"),
    ({"a": np.zeros((2, 2))}, {}, ValueError, "must be 1-D"),
    ({"a": [1]}, {"samples": 5}, ValueError, "samples is for method='random'"),
    ({"a": (0, 1)}, {"method": "random"}, ValueError, "needs samples"),
    ({"a": (1, 0)}, {"method": "random", "samples": 3}, ValueError, "low is above high"),
    ({"a": (0, 1, 2)}, {"method": "random", "samples": 3}, ValueError, r"\(low, high\)"),
    ({"a": [1]}, {"method": "sobol"}, ValueError, "'grid' or 'random'"),
    ({"a": [1]}, {"executor": "threads"}, ValueError, "serial, processes, dask"),
    ({"a": [1]}, {"on_error": "skip"}, ValueError, "'raise' or 'nan'"),
    ({"a": [1]}, {"workers": 0}, ValueError, "workers must be a positive"),
    ({"motion..feed": [1]}, {"base": CH5}, ValueError, "not a path into the machine dict"),
    ({"motion.max_feed_mm_min": [1]}, {}, ValueError, "no base machine"),
    ({"base_joints[9][0]": [1.0]}, {"base": CH5}, ValueError, "index 9 is out of range"),
    ({"tool[0]": [1.0]}, {"base": {"name": "x"}}, ValueError, "no 'tool' to index"),
    ({"a": [1]}, {"base": 42}, TypeError, "base must be a machine file path"),
    ({"a": [1]}, {"base": layouts.hexapod}, TypeError, "functools.partial"),
])
def test_bad_specs_raise_clear_errors(space, kwargs, error, match):
    with pytest.raises(error, match=match):
        pkm.sweep(scalar_only, space, **{"executor": "serial", **kwargs})
