"""Poses in degrees where a caller prefers them: `angles="deg"` on the functions and methods that take or return
poses [x, y, z mm, a, b, c]. Radians stay the default (`angles="rad"`), as in the compiled core; files and the CLI
use degrees, so a script that reads poses from them can pass `angles="deg"` instead of converting."""

import functools

import numpy as np

_RAD_PER_DEG = np.pi / 180.0


def _scaled_angles(poses, factor):
    values = np.array(poses, dtype=np.float64, copy=True)
    if values.ndim in (1, 2) and values.shape[-1] == 6:  # other shapes: the core names what is wrong
        values[..., 3:6] *= factor
    return values


def _poses_in_degrees(result):
    if isinstance(result, tuple):  # fk(..., info=True): (poses, info)
        return (_scaled_angles(result[0], 1.0 / _RAD_PER_DEG), *result[1:])
    return _scaled_angles(result, 1.0 / _RAD_PER_DEG)


def angles_keyword(function, pose_arguments, returns_poses=False):
    """`function` taking angles="rad"|"deg": the poses among `pose_arguments` ({name: position}) are converted
    from degrees before the call, and returned poses back to degrees when `returns_poses`."""

    @functools.wraps(function)
    def with_angles(*args, angles="rad", **kwargs):
        if angles not in ("rad", "deg"):
            raise ValueError(f"angles must be 'rad' or 'deg', not {angles!r}")
        if angles == "rad":
            return function(*args, **kwargs)
        args = list(args)
        for name, position in pose_arguments.items():
            if kwargs.get(name) is not None:
                kwargs[name] = _scaled_angles(kwargs[name], _RAD_PER_DEG)
            elif position < len(args) and args[position] is not None:
                args[position] = _scaled_angles(args[position], _RAD_PER_DEG)
        result = function(*args, **kwargs)
        return _poses_in_degrees(result) if returns_poses else result

    with_angles.extra_keywords = ("angles",)
    return with_angles


# (name, the pose arguments and their positions counting self, whether it returns poses)
_MACHINE_METHODS = [("ik", {"poses": 1}, False), ("fk", {"guess": 2}, True), ("jacobian", {"poses": 1}, False),
                    ("conditioning", {"poses": 1}, False), ("pose_from_abc", {"poses": 1}, True),
                    ("abc_from_pose", {"poses": 1}, True)]
_FUNCTIONS = [("modes", {"pose": 1}, False), ("compliance", {"pose": 1}, False)]


def wrap(machine_class, namespace):
    for name, poses, returns_poses in _MACHINE_METHODS:
        setattr(machine_class, name, angles_keyword(getattr(machine_class, name), poses, returns_poses))
    for name, poses, returns_poses in _FUNCTIONS:
        namespace[name] = angles_keyword(namespace[name], poses, returns_poses)
