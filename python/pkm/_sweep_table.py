"""pkm.sweep's table: the points' parameters and the chunks' results as one structured array or DataFrame."""

from __future__ import annotations

import itertools
import math
from typing import Any, Dict, List

import numpy as np

from ._sweep_chunks import _ChunkResults



def _column(values: List[Any]) -> np.ndarray:
    """A numpy column for a list of values; None marks a failed point (NaN in a numeric column)."""
    kinds = set(map(type, values))  # one pass in C: the table of a big sweep is built in the caller's process
    missing = type(None) in kinds
    kinds.discard(type(None))
    if kinds == {bool} and not missing:
        return np.array(values, dtype=bool)
    whole_numbers = kinds == {int} and not missing
    if whole_numbers and -2**63 <= min(values) and max(values) < 2**63:
        return np.array(values, dtype=np.int64)
    if kinds <= {bool, int, float} and not whole_numbers:
        if not missing:
            return np.array(values, dtype=np.float64)
        return np.array([math.nan if v is None else v for v in values], dtype=np.float64)
    if kinds == {str}:
        return np.array(["" if v is None else v for v in values], dtype=str)
    column = np.empty(len(values), dtype=object)
    column[:] = values
    return column


def _table(names: List[str], points: List[tuple], chunks: List[_ChunkResults], on_error: str, kind: str) -> Any:
    result_keys: Dict[str, None] = {}
    for chunk in chunks:
        result_keys.update(dict.fromkeys(chunk.keys))
    for key in result_keys:
        if key in names or (on_error == "nan" and key == "error"):
            raise ValueError(f"pkm.sweep: evaluate returned {key!r}, which is also a column of the table "
                             f"(a parameter{' or error' if on_error == 'nan' else ''}); rename it")
    columns: Dict[str, np.ndarray] = {}
    for position, name in enumerate(names):
        columns[name] = _column([point[position] for point in points])
    for key in result_keys:
        columns[key] = _column(list(itertools.chain.from_iterable(chunk.column(key) for chunk in chunks)))
    if on_error == "nan":
        columns["error"] = np.array(list(itertools.chain.from_iterable(chunk.errors for chunk in chunks)), dtype=str)
    if kind != "numpy":
        try:
            import pandas
        except ImportError:
            if kind == "pandas":
                raise ImportError("pkm.sweep: table='pandas' needs pandas; table='numpy' gives a structured "
                                  "array") from None
        else:
            return pandas.DataFrame(columns)
    table = np.empty(len(points), dtype=[(name, column.dtype) for name, column in columns.items()])
    for name, column in columns.items():
        table[name] = column
    return table
