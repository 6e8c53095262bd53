"""pkm: kinematics, motion planning and analyses of parallel-kinematic machines, from Python (docs/python.md).

Lengths are in mm, angles in rad unless a name says otherwise (`_deg`), times in s, forces in N.
"""

from ._errors import (Error, FileIOError, InputError, LimitExceededError, MachineFileError, NotConvergedError,
                      ProgramError, SingularError, UnreachableError, UnsupportedError, WrongBranchError)
from ._pkm import *  # noqa: F401,F403  (the compiled core)
