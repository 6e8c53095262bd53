"""A misspelt keyword named in one line: pybind11 answers an unknown keyword with every overload's signature (ten
lines and more); the functions and methods of the compiled core are wrapped so that the error names the keyword
and the nearest accepted one, as a Python function would."""

import difflib
import functools
import re

# "ik(self: pkm._pkm.Machine, poses: object, *, errors: str = 'raise') -> object": the parameter names are the
# words before ':' in the parentheses of each signature line pybind11 writes at the top of the docstring.
_SIGNATURE = re.compile(r"^\s*(?:\d+\.\s*)?(\w+)\((.*)\)\s*->", re.MULTILINE)
_PARAMETER = re.compile(r"(?:^|,\s*|\*,\s*)(\w+)\s*:")


def _accepted_keywords(function):
    names = set()
    for signature in _SIGNATURE.finditer(getattr(function, "__doc__", None) or ""):
        names.update(_PARAMETER.findall(signature.group(2)))
    names.discard("self")
    # Keywords a Python wrapper adds before the compiled function (angles="deg": _angles.py).
    names.update(getattr(function, "extra_keywords", ()))
    return names


def named_keywords(function):
    """`function`, refusing an unknown keyword in one line ("did you mean …?"); unchanged when its docstring
    gives no signature to check against."""
    accepted = _accepted_keywords(function)
    if not accepted:
        return function

    @functools.wraps(function)
    def checked(*args, **kwargs):
        for keyword in kwargs:
            if keyword not in accepted:
                near = difflib.get_close_matches(keyword, sorted(accepted), n=1)
                hint = f"; did you mean '{near[0]}'?" if near else f"; it takes {', '.join(sorted(accepted))}"
                raise TypeError(f"{function.__name__}() got an unexpected keyword argument '{keyword}'{hint}")
        return function(*args, **kwargs)

    return checked


def wrap_module(namespace, module, classes):
    """Replaces the compiled functions of `module` found in `namespace`, and the methods of `classes`."""
    for name in dir(module):
        value = getattr(module, name)
        if name.startswith("__") or isinstance(value, type) or not callable(value):
            continue
        current = namespace.get(name)
        if current is value or getattr(current, "__wrapped__", None) is value:
            namespace[name] = named_keywords(current)
    for cls in classes:
        for name, value in list(vars(cls).items()):
            if name.startswith("__"):
                continue
            if isinstance(value, staticmethod):
                setattr(cls, name, staticmethod(named_keywords(value.__func__)))
            elif callable(value) and not isinstance(value, classmethod):
                setattr(cls, name, named_keywords(value))
