"""pkm.sweep's design space (the points of a grid or a random sample) and the machine variants at them."""

from __future__ import annotations

import copy
import inspect
import itertools
import math
import os
import re
from collections.abc import Mapping
from numbers import Integral, Real
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np


#: Top-level keys of machine files (docs/machine-file.md): a parameter with one of these names replaces the key.
MACHINE_KEYS = frozenset({
    "name", "description", "type", "angles", "tool", "limits", "motion", "masses", "dynamics", "stiffness",
    "servo", "drives", "base_joint_axes", "platform_joint_axes", "home", "calibration", "base_joints",
    "platform_joints", "base_axes", "cardan", "center_joint", "guides", "strut_lengths", "branch", "circle",
    "joint_heights"
})

#: The most points one task carries by default: enough that a task's start-up is small beside its work.
TASK_POINTS = 2000

_EXECUTORS = ("serial", "processes", "dask")
_PATH_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_STEP_RE = re.compile(r"\.([A-Za-z_][A-Za-z0-9_]*)|\[(-?[0-9]+)\]")




def _native(value: Any) -> Any:
    """Plain Python data for a parameter value (numpy scalars and arrays become numbers and lists)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (list, tuple)):
        return [_native(v) for v in value]
    return value


def _check_names(space: Any) -> List[str]:
    if not isinstance(space, Mapping):
        raise TypeError(f"pkm.sweep: space must be a dict of parameter name -> values, got {type(space).__name__}")
    if not space:
        raise ValueError("pkm.sweep: space is empty; give at least one parameter")
    names = list(space)
    for name in names:
        if not isinstance(name, str) or not name:
            raise TypeError(f"pkm.sweep: parameter names must be non-empty strings, got {name!r}")
    return names


def _grid_values(name: str, values: Any) -> list:
    if isinstance(values, (str, bytes)) or isinstance(values, Mapping) or not hasattr(values, "__iter__"):
        raise TypeError(f"pkm.sweep: space[{name!r}] must be a list of values for a grid, got {values!r}"
                        f" (a single value: [{values!r}])")
    if isinstance(values, np.ndarray) and values.ndim != 1:
        raise ValueError(f"pkm.sweep: space[{name!r}] must be 1-D, got an array of shape {values.shape}")
    listed = [_native(v) for v in values]
    if not listed:
        raise ValueError(f"pkm.sweep: space[{name!r}] has no values")
    return listed


def _random_range(name: str, bounds: Any) -> Tuple[float, float]:
    message = (f"pkm.sweep: with method='random', space[{name!r}] must be (low, high), two finite numbers, "
               f"got {bounds!r}")
    if isinstance(bounds, (str, bytes)) or not hasattr(bounds, "__len__") or len(bounds) != 2:
        raise ValueError(message)
    low, high = (_native(v) for v in bounds)
    if not all(isinstance(v, Real) and not isinstance(v, bool) and math.isfinite(v) for v in (low, high)):
        raise ValueError(message)
    if low > high:
        raise ValueError(f"pkm.sweep: space[{name!r}] = {bounds!r}: low is above high")
    return float(low), float(high)


def design_points(space: Mapping[str, Any], method: str = "grid", samples: Optional[int] = None,
                  seed: Any = 0) -> Tuple[List[str], List[tuple]]:
    """The parameter names and the points (one tuple of values per point, in the names' order) of a design space.

    grid:   the Cartesian product of the value lists, in the order of nested loops over the names as the space
            lists them: the last name varies fastest (itertools.product order).
    random: `samples` points; numpy.random.default_rng(seed).uniform(lows, highs, size=(samples, len(names))),
            so row i is point i and the same seed gives the same points.
    """
    names = _check_names(space)
    if method == "grid":
        if samples is not None:
            raise ValueError("pkm.sweep: samples is for method='random'; a grid has one point per combination")
        columns = [_grid_values(name, space[name]) for name in names]
        return names, list(itertools.product(*columns))
    if method == "random":
        if isinstance(samples, bool) or not isinstance(samples, Integral) or samples < 1:
            raise ValueError(f"pkm.sweep: method='random' needs samples, a positive whole number, got {samples!r}")
        ranges = [_random_range(name, space[name]) for name in names]
        rng = np.random.default_rng(seed)
        lows = np.array([r[0] for r in ranges])
        highs = np.array([r[1] for r in ranges])
        drawn = rng.uniform(lows, highs, size=(int(samples), len(names)))
        return names, [tuple(row) for row in drawn.tolist()]
    raise ValueError(f"pkm.sweep: method must be 'grid' or 'random', got {method!r}")


# ---- variants of the base machine ---------------------------------------------------------------------------------

def _parse_path(name: str) -> Optional[List[Any]]:
    """The steps of a path name (`motion.max_feed_mm_min` -> ['motion', 'max_feed_mm_min'], `base_joints[2][0]` ->
    ['base_joints', 2, 0]), or None for a plain name."""
    if "." not in name and "[" not in name:
        return None
    head = _PATH_RE.match(name)
    steps: List[Any] = []
    position = 0
    if head:
        steps.append(head.group(0))
        position = head.end()
    while head and position < len(name):
        step = _STEP_RE.match(name, position)
        if not step:
            break
        steps.append(step.group(1) if step.group(1) is not None else int(step.group(2)))
        position = step.end()
    if not head or position != len(name):
        raise ValueError(f"pkm.sweep: parameter {name!r} is not a path into the machine dict; write keys with dots "
                         f"and list indices in brackets, e.g. 'motion.max_feed_mm_min' or 'base_joints[2][0]'")
    return steps


def _set_path(machine: Dict[str, Any], name: str, steps: Sequence[Any], value: Any) -> None:
    container: Any = machine
    for depth, step in enumerate(steps):
        last = depth == len(steps) - 1
        where = name if last else "".join(
            (f".{s}" if isinstance(s, str) else f"[{s}]") for s in steps[:depth + 1]).lstrip(".")
        if isinstance(step, str):
            if not isinstance(container, dict):
                raise ValueError(f"pkm.sweep: {name}: {where!r} needs a mapping, the machine has "
                                 f"{type(container).__name__} there")
            if last:
                container[step] = value
            else:
                if step not in container:
                    if isinstance(steps[depth + 1], int):
                        raise ValueError(f"pkm.sweep: {name}: the machine has no {where!r} to index")
                    container[step] = {}
                container = container[step]
        else:
            if not isinstance(container, list):
                raise ValueError(f"pkm.sweep: {name}: {where!r} indexes a list, the machine has "
                                 f"{type(container).__name__} there")
            if not -len(container) <= step < len(container):
                raise ValueError(f"pkm.sweep: {name}: index {step} is out of range ({len(container)} entries)")
            if last:
                container[step] = value
            else:
                container = container[step]


def _callable_arguments(base: Callable) -> Tuple[inspect.Signature, Optional[set], bool]:
    """A callable base's signature, the names it takes as keywords, and whether it takes any (**kwargs)."""
    try:
        signature = inspect.signature(base)
    except (TypeError, ValueError) as error:
        raise TypeError(f"pkm.sweep: cannot read the arguments of base {base!r}: {error}") from None
    named = set()
    any_keyword = False
    for parameter in signature.parameters.values():
        if parameter.kind is inspect.Parameter.VAR_KEYWORD:
            any_keyword = True
        elif parameter.kind in (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY):
            named.add(parameter.name)
    return signature, named, any_keyword


class _Variants:
    """How each parameter of a point acts: an argument of a callable base, a path into the machine dict, or only
    a value for evaluate. Built once in the caller's process and sent to the workers with the task."""

    def __init__(self, base: Any, names: List[str]):
        self.base_dict: Optional[Dict[str, Any]] = None
        self.base_callable: Optional[Callable] = None
        self.builder_names: List[str] = []
        self.paths: List[Tuple[str, List[Any]]] = []
        self.machine_names: List[str] = []
        parsed = {name: _parse_path(name) for name in names}
        if base is None:
            overrides = [name for name in names if parsed[name] is not None]
            if overrides:
                raise ValueError(f"pkm.sweep: {overrides[0]!r} overrides a machine entry, but no base machine was "
                                 f"given (base=path, dict or callable)")
            return
        if isinstance(base, (str, os.PathLike)):
            from . import read_machine_dict  # the compiled reader: the file's data as plain Python
            base = read_machine_dict(os.fspath(base))
        if isinstance(base, Mapping):
            self.base_dict = copy.deepcopy(dict(base))
            top_keys = MACHINE_KEYS | set(self.base_dict)
        elif callable(base):
            self.base_callable = base
            signature, named, any_keyword = _callable_arguments(base)
            self.builder_names = [name for name in names
                                  if parsed[name] is None and (name in named or (any_keyword and name not in
                                                                                 MACHINE_KEYS))]
            try:
                signature.bind(**{name: None for name in self.builder_names})
            except TypeError as error:
                raise TypeError(f"pkm.sweep: base {getattr(base, '__name__', base)!r} cannot be called with the "
                                f"space's parameters {self.builder_names}: {error}; bind the other arguments "
                                f"with functools.partial") from None
            top_keys = MACHINE_KEYS
        else:
            raise TypeError(f"pkm.sweep: base must be a machine file path, a machine dict or a callable returning "
                            f"one, got {type(base).__name__}")
        for name in names:
            if name in self.builder_names:
                continue
            if parsed[name] is not None:
                self.paths.append((name, parsed[name]))
            elif name in top_keys:
                self.paths.append((name, [name]))
        self.machine_names = self.builder_names + [name for name, _ in self.paths]

    @property
    def has_machine(self) -> bool:
        return self.base_dict is not None or self.base_callable is not None

    def key(self, params: Dict[str, Any]) -> tuple:
        return tuple(params[name] for name in self.machine_names)

    def machine_dict(self, params: Dict[str, Any]) -> Dict[str, Any]:
        if self.base_callable is not None:
            built = self.base_callable(**{name: params[name] for name in self.builder_names})
            if not isinstance(built, Mapping):
                raise TypeError(f"pkm.sweep: base returned {type(built).__name__}, not a machine dict")
            machine = copy.deepcopy(dict(built))
        else:
            machine = copy.deepcopy(self.base_dict)
        for name, steps in self.paths:
            _set_path(machine, name, steps, copy.deepcopy(params[name]))
        return machine
