"""Machine.from_dict's text: a dict of machine-file entries as pretty-printed JSON (JSON is YAML, so the
machine-file reader takes it as it is). One key or list item per line, so that an error's line and column
point at the entry in this text (pkm.MachineFileError.key names it either way)."""

from __future__ import annotations

import json
import math
import numbers
from collections.abc import Mapping
from typing import Any

from ._errors import MachineFileError


def _where(path: str, key: Any) -> str:
    return f"{path}.{key}" if path else str(key)


def _plain(value: Any, path: str, source: str) -> Any:
    """`value` as JSON-ready data: numpy scalars and arrays become numbers and lists."""
    if isinstance(value, Mapping):
        out = {}
        for key, item in value.items():
            if not isinstance(key, str):
                raise MachineFileError(f"{source}: {_where(path, key)}: keys must be texts, got {type(key).__name__}",
                                       "bad_input", source, None, None, _where(path, key))
            out[key] = _plain(item, _where(path, key), source)
        return out
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):  # numpy arrays and scalars
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(item, f"{path}[{i}]", source) for i, item in enumerate(value)]
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        number = float(value)
        if not math.isfinite(number):
            raise MachineFileError(f"{source}: {path}: expected a finite number, got {number}", "bad_input", source,
                                   None, None, path)
        return number
    raise MachineFileError(f"{source}: {path}: cannot be written to a machine file ({type(value).__name__})",
                           "bad_input", source, None, None, path)


def machine_json_text(data: Mapping, source: str = "<dict>") -> str:
    """The machine-file text (JSON) of `data`; MachineFileError naming the key for values JSON cannot hold."""
    if not isinstance(data, Mapping):
        raise TypeError(f"Machine.from_dict needs a dict of machine-file entries, got {type(data).__name__}")
    return json.dumps(_plain(data, "", source), indent=2, ensure_ascii=False) + "\n"
