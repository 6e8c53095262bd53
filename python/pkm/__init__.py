"""pkm: kinematics, motion planning and analyses of parallel-kinematic machines, from Python (docs/python.md).

Lengths are in mm, angles in rad unless a name says otherwise (`_deg`) or a call says angles="deg" (the functions
and methods that take or return poses), times in s, forces in N.
"""

from ._errors import (Error, FileIOError, InputError, LimitExceededError, MachineFileError, NotConvergedError,
                      ProgramError, SingularError, UnreachableError, UnsupportedError, WrongBranchError)
from ._pkm import *  # noqa: F401,F403  (the compiled core)
from ._pkm import Machine, get_threads, read_machine_dict, set_threads  # noqa: F401  (named for editors)
from ._pkm import __version__  # noqa: F401  (pkm --version's, from CMake's project version)
from . import layouts  # noqa: E402  (parametric machine dicts for design studies)
from .sweep import MACHINE_KEYS, design_points, sweep  # noqa: E402,F401  (design-space sweeps)

from . import _angles, _keywords  # noqa: E402
from . import _pkm  # noqa: E402

# angles="deg" where poses are given or returned; then an unknown keyword is named in one line with the nearest
# accepted one (pybind11 would print every overload's signature).
_angles.wrap(Machine, globals())
_keywords.wrap_module(globals(), _pkm, [Machine])
