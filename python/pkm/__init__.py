"""pkm: kinematics, motion planning and analyses of parallel-kinematic machines, from Python (docs/python.md).

Lengths are in mm, angles in rad unless a name says otherwise (`_deg`), times in s, forces in N.
"""

from ._errors import (Error, FileIOError, InputError, LimitExceededError, MachineFileError, NotConvergedError,
                      ProgramError, SingularError, UnreachableError, UnsupportedError, WrongBranchError)
from ._pkm import *  # noqa: F401,F403  (the compiled core)
from ._pkm import Machine, get_threads, read_machine_dict, set_threads  # noqa: F401  (named for editors)
from . import layouts  # noqa: E402  (parametric machine dicts for design studies)
from .sweep import MACHINE_KEYS, design_points, sweep  # noqa: E402,F401  (design-space sweeps)
