"""The exceptions pkm raises. Every one carries where its input was wrong, when it came from a file.

    Error                 base of all; attributes code, file, line, column, key (None where not known)
    ├─ InputError         a malformed argument, value or file (ValueError too)
    │  ├─ MachineFileError   a machine file (YAML): file, line, column, key
    │  └─ ProgramError       a part program (G-code, CL data): file, line, column
    ├─ UnreachableError   a pose no actuator setting reaches
    ├─ NotConvergedError  an iterative solver stopped short of its tolerance
    ├─ SingularError      a singular or badly conditioned configuration
    ├─ WrongBranchError   a solution exists, but in another assembly mode
    ├─ LimitExceededError an actuator or joint limit is violated
    ├─ UnsupportedError   the mechanism does not offer this operation
    └─ FileIOError        a file could not be read or written (OSError too)
"""

from __future__ import annotations

from typing import Optional


class Error(Exception):
    """Base of pkm's exceptions: the library's one-line message, its error code and the input location."""

    def __init__(self, message: str, code: str = "", file: Optional[str] = None, line: Optional[int] = None,
                 column: Optional[int] = None, key: Optional[str] = None):
        super().__init__(message)
        self.message = message
        self.code = code
        self.file = file
        self.line = line
        self.column = column
        self.key = key


class InputError(Error, ValueError):
    """A malformed argument, value or input file."""


class MachineFileError(InputError):
    """A machine file (YAML) is malformed or invalid: `file`, `line`, `column` and `key` say where."""


class ProgramError(InputError):
    """A part program (G-code or CL data) is malformed: `file`, `line` and `column` say where."""


class UnreachableError(Error):
    """A pose that no actuator setting reaches."""


class NotConvergedError(Error):
    """An iterative solver (forward kinematics, identification) stopped without meeting its tolerance."""


class SingularError(Error):
    """A singular or badly conditioned configuration."""


class WrongBranchError(Error):
    """A solution exists but in another assembly mode or branch than the one asked for."""


class LimitExceededError(Error):
    """An actuator or joint limit is violated."""


class UnsupportedError(Error):
    """The mechanism does not offer this operation (for example all assembly modes of a glide machine)."""


class FileIOError(Error, OSError):
    """A file could not be read or written."""


_BY_CODE = {
    "unreachable": UnreachableError,
    "not_converged": NotConvergedError,
    "singular": SingularError,
    "wrong_branch": WrongBranchError,
    "limit_exceeded": LimitExceededError,
    "unsupported": UnsupportedError,
    "io": FileIOError,
}

_PROGRAM_SUFFIXES = (".ngc", ".nc", ".gcode", ".tap", ".cl", ".cls", ".apt")


def from_error(code: str, message: str, file: str, line: int, column: int, key: str) -> Error:
    """The exception for a library error (called by the compiled module)."""
    if code == "bad_input":
        if file and file.lower().endswith(_PROGRAM_SUFFIXES):
            cls = ProgramError
        elif file and (key or file.lower().endswith((".yaml", ".yml")) or file == "<dict>"):
            cls = MachineFileError
        else:
            cls = InputError
    else:
        cls = _BY_CODE.get(code, Error)
    return cls(message, code, file or None, line or None, column or None, key or None)
