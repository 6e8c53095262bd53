"""pkm.sweep's unit of work: one chunk of points evaluated in a worker, its results by column."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Callable, Dict, List, Optional, Sequence

import numpy as np

from ._sweep_space import _Variants



def _scalar(key: str, value: Any) -> Any:
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    elif isinstance(value, np.generic):
        value = value.item()
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    shape = f" of shape {value.shape}" if hasattr(value, "shape") else ""
    raise TypeError(f"evaluate must return a scalar or a dict of scalars; {key!r} is a {type(value).__name__}{shape}")


def _as_results(value: Any) -> Dict[str, Any]:
    if isinstance(value, Mapping):
        results = {}
        for key, item in value.items():
            if not isinstance(key, str) or not key:
                raise TypeError(f"evaluate must return a dict with string keys, got the key {key!r}")
            results[key] = _scalar(key, item)
        return results
    return {"value": _scalar("value", value)}


class _Task:
    """What every chunk needs: the function, the variants and the error policy (pickled once per chunk)."""

    def __init__(self, evaluate: Callable, variants: _Variants, names: List[str], on_error: str):
        self.evaluate = evaluate
        self.variants = variants
        self.names = names
        self.on_error = on_error


class _ChunkResults:
    """A chunk's results by column (cheaper to send back than a dict per point): the keys in the order evaluate
    first returned them, one list of values per key (None where a point lacks it or failed), and per point its
    error message ('' for success)."""

    def __init__(self) -> None:
        self.keys: List[str] = []
        self.columns: List[list] = []
        self.errors: List[str] = []
        self._index: Dict[str, int] = {}

    def add(self, results: Optional[Dict[str, Any]], error: str) -> None:
        row = len(self.errors)
        for key, value in (results or {}).items():
            index = self._index.get(key)
            if index is None:
                index = self._index[key] = len(self.keys)
                self.keys.append(key)
                self.columns.append([None] * row)
            self.columns[index].append(value)
        self.errors.append(error)
        for column in self.columns:
            if len(column) == row:
                column.append(None)

    def column(self, key: str) -> list:
        index = self._index.get(key)
        return self.columns[index] if index is not None else [None] * len(self.errors)

    def __getstate__(self) -> tuple:
        return self.keys, self.columns, self.errors

    def __setstate__(self, state: tuple) -> None:
        self.keys, self.columns, self.errors = state
        self._index = {key: index for index, key in enumerate(self.keys)}


def _run_chunk(task: _Task, first_index: int, points: Sequence[tuple]) -> _ChunkResults:
    """Evaluates consecutive points; those of the same variant share one Machine."""
    from . import Machine  # the compiled class; imported here so that the worker imports pkm itself

    chunk = _ChunkResults()
    last_key: Any = object()
    machine: Any = None
    for offset, values in enumerate(points):
        params = dict(zip(task.names, values))
        try:
            if task.variants.has_machine:
                key = task.variants.key(params)
                if machine is None or key != last_key:
                    machine = None
                    machine = Machine.from_dict(task.variants.machine_dict(params))
                    last_key = key
            results = _as_results(task.evaluate(machine, params))
        except Exception as error:  # noqa: BLE001 (the user's evaluate may raise anything)
            if task.on_error == "raise":
                error.add_note(f"pkm.sweep: at point {first_index + offset}, parameters {params}")
                raise
            chunk.add(None, f"{type(error).__name__}: {str(error) or type(error).__name__}")
        else:
            chunk.add(results, "")
    return chunk
