"""Parametric machines for design studies: machine dicts in the machine-file format (docs/machine-file.md).

Each function returns a plain dict, exactly what `pkm.Machine.from_dict` takes and what a machine file holds after
reading (lengths in mm, angles in degrees, as in the files). Pass the function itself (or a `functools.partial` of
it) as `base=` to `pkm.sweep`: the sweep calls it with the design parameters whose names are its arguments.

    >>> import pkm
    >>> from pkm import layouts
    >>> m = pkm.Machine.from_dict(layouts.hexapod(500, 300, platform_separation_deg=30))   # hexapod_ch3_delta30.yaml

Joint positions on a circle are computed with the angle reduced to its first octant and the exact values at
multiples of 30° and 45°, so that symmetric joints are exact mirror images and the shipped example files
(`hexapod_ch3.yaml`, `hexapod_ch3_delta30.yaml`, `hexapod_ch5.yaml`, `tripod.yaml`) are reproduced to the last bit.
"""

from __future__ import annotations

import math
from numbers import Real
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

__all__ = ["hexapod", "tripod", "circle_point"]

_EXACT_COS_SIN = {
    0.0: (1.0, 0.0),
    30.0: (math.sqrt(3.0) / 2.0, 0.5),
    45.0: (math.sqrt(0.5), math.sqrt(0.5)),
    60.0: (0.5, math.sqrt(3.0) / 2.0),
}


def _cos_sin_deg(angle_deg: float) -> Tuple[float, float]:
    """cos and sin of an angle in degrees, exact at multiples of 30° and 45° and mirror-symmetric across quadrants."""
    reduced = float(angle_deg) % 360.0
    quadrant = int(reduced // 90.0)
    rest = reduced - 90.0 * quadrant
    if rest in _EXACT_COS_SIN:
        c, s = _EXACT_COS_SIN[rest]
    elif rest <= 45.0:
        c, s = math.cos(math.radians(rest)), math.sin(math.radians(rest))
    else:  # from the complement, so that rest and 90° - rest give mirrored values
        s, c = math.cos(math.radians(90.0 - rest)), math.sin(math.radians(90.0 - rest))
    return [(c, s), (-s, c), (-c, -s), (s, -c)][quadrant]


def circle_point(radius_mm: float, angle_deg: float, z_mm: float = 0.0) -> list:
    """The point [x, y, z] (mm) at `angle_deg` (from +x towards +y) on a circle of `radius_mm` centred on the z axis."""
    c, s = _cos_sin_deg(angle_deg)
    return [radius_mm * c, radius_mm * s, float(z_mm)]


def _positive(name: str, value: Any) -> float:
    if not isinstance(value, Real) or isinstance(value, bool) or not math.isfinite(value) or value <= 0.0:
        raise ValueError(f"pkm.layouts: {name} must be a positive finite number, got {value!r}")
    return float(value)


def _angle_in(name: str, value: Any, low_deg: float, high_deg: float) -> float:
    if not isinstance(value, Real) or isinstance(value, bool) or not math.isfinite(value) or not (
            low_deg <= value <= high_deg):
        raise ValueError(f"pkm.layouts: {name} must be an angle in [{low_deg:g}, {high_deg:g}] deg, got {value!r}")
    return float(value)


def _tool_point(tool_mm: Union[float, Sequence[float]]) -> list:
    if isinstance(tool_mm, Real) and not isinstance(tool_mm, bool):
        return [0.0, 0.0, float(tool_mm)]
    try:
        point = [float(v) for v in tool_mm]  # type: ignore[union-attr]
    except TypeError:
        point = []
    if len(point) != 3 or not all(math.isfinite(v) for v in point):
        raise ValueError(f"pkm.layouts: tool_mm must be a distance along the platform's z axis or 3 numbers "
                         f"[x, y, z] in the platform frame, got {tool_mm!r}")
    return point


def _finish(machine: Dict[str, Any], tool: list, height_mm: float, home: Optional[Sequence[float]],
            limits: Optional[Mapping[str, Any]], motion: Optional[Mapping[str, Any]],
            sections: Mapping[str, Any]) -> Dict[str, Any]:
    """tool, limits, motion, the other sections, and home (level, the tool point above the platform-joint plane)."""
    machine["tool"] = tool
    if limits is not None:
        machine["limits"] = dict(limits)
    if motion is not None:
        machine["motion"] = dict(motion)
    for key, value in sections.items():
        if key in machine:
            raise ValueError(f"pkm.layouts: the section {key!r} is computed from the layout's parameters")
        machine[key] = value
    if home is None:
        home = [tool[0], tool[1], height_mm + tool[2], 0.0, 0.0, 0.0]
    machine["home"] = [float(v) for v in home]
    return machine


def hexapod(base_radius_mm: float, platform_radius_mm: float, *, base_separation_deg: float = 60.0,
            platform_separation_deg: float = 0.0, height_mm: float = 500.0,
            tool_mm: Union[float, Sequence[float]] = 200.0, angles: str = "krylov", pair_angle_deg: float = 30.0,
            limits: Optional[Mapping[str, Any]] = None, motion: Optional[Mapping[str, Any]] = None,
            name: Optional[str] = None, home: Optional[Sequence[float]] = None, **sections: Any) -> Dict[str, Any]:
    """A Stewart–Gough hexapod (type `hexapod`) with its joints on two circles, as a machine dict.

    The six struts form three V-shaped pairs. Pair k (struts 2k and 2k+1, k = 0, 1, 2) is centred at the angle
    φ_k = pair_angle_deg + 120°·k:

      - platform joints 2k and 2k+1 at φ_k ∓ platform_separation_deg/2 on the circle of `platform_radius_mm`
        (0: the pair's joints merge, a 6-3 hexapod, Smirnov 2019's "pairwise merged"; δ of its Table 2);
      - base joints 2k and 2k+1 at φ_k ∓ (60° − base_separation_deg/2) on the circle of `base_radius_mm`, so that
        `base_separation_deg` is the angle between the neighbouring base joints of adjacent pairs (2k+1 and 2k+2):
        60 puts the base joints every 60° (Smirnov 2019's machines), 0 merges them (a 3-3 layout at both 0).

    The platform frame's origin is the centre of the platform-joint circle; the joints lie in its z = 0 plane, and
    `height_mm` is that plane's height above the base-joint plane at home. `tool_mm` is the tool point in the
    platform frame: a distance along the platform's z axis or [x, y, z]. `home` defaults to the level pose with the
    platform at `height_mm`. Angles are `angles` (abc, krylov or euler_zxz: Smirnov 2019's machines use krylov).

    `limits` and `motion` become those sections; any other keyword (dynamics=..., drives=..., description=...)
    is copied in as a top-level section. Defaults give the chapter-3 hexapod's shape:

      hexapod(500, 300)                              -> examples/machines/hexapod_ch3.yaml's joints
      hexapod(500, 300, platform_separation_deg=30)  -> hexapod_ch3_delta30.yaml's
      hexapod(400, 200, height_mm=550, tool_mm=150)  -> hexapod_ch5.yaml's
    """
    base_r = _positive("base_radius_mm", base_radius_mm)
    platform_r = _positive("platform_radius_mm", platform_radius_mm)
    base_sep = _angle_in("base_separation_deg", base_separation_deg, 0.0, 120.0)
    platform_sep = _angle_in("platform_separation_deg", platform_separation_deg, 0.0, 120.0)
    height = _positive("height_mm", height_mm)
    pair_angle = _angle_in("pair_angle_deg", pair_angle_deg, -360.0, 360.0)
    tool = _tool_point(tool_mm)
    base_half_deg = 60.0 - base_sep / 2.0
    base_joints, platform_joints = [], []
    for k in range(3):
        centre_deg = pair_angle + 120.0 * k
        for side in (-1.0, 1.0):
            base_joints.append(circle_point(base_r, centre_deg + side * base_half_deg))
            platform_joints.append(circle_point(platform_r, centre_deg + side * platform_sep / 2.0))
    if name is None:
        name = (f"hexapod R{base_r:g}/{platform_r:g} mm, separations {base_sep:g}/{platform_sep:g} deg, "
                f"height {height:g} mm")
    machine: Dict[str, Any] = {"name": name, "type": "hexapod", "angles": angles, "base_joints": base_joints,
                               "platform_joints": platform_joints}
    return _finish(machine, tool, height, home, limits, motion, sections)


def tripod(base_radius_mm: float, platform_radius_mm: float, *, height_mm: float = 700.0,
           tool_mm: Union[float, Sequence[float]] = 100.0, angles: str = "abc", first_joint_deg: float = 90.0,
           limits: Optional[Mapping[str, Any]] = None, motion: Optional[Mapping[str, Any]] = None,
           name: Optional[str] = None, home: Optional[Sequence[float]] = None, **sections: Any) -> Dict[str, Any]:
    """A spatial 3-RPS tripod (type `tripod`) as a machine dict.

    Base (revolute) joints on the circle of `base_radius_mm` and platform (spherical) joints on the circle of
    `platform_radius_mm`, both at first_joint_deg + 0°, 120°, 240°; each revolute axis horizontal and tangent to the
    base circle, so every strut swings in the vertical plane through the base centre. `height_mm` is the
    platform-joint plane's height above the base at home, `tool_mm` the tool point in the platform frame (a distance
    along z or [x, y, z]); the other arguments as for `hexapod`.

      tripod(400, 200) -> examples/machines/tripod.yaml's joints and axes
    """
    base_r = _positive("base_radius_mm", base_radius_mm)
    platform_r = _positive("platform_radius_mm", platform_radius_mm)
    height = _positive("height_mm", height_mm)
    first = _angle_in("first_joint_deg", first_joint_deg, -360.0, 360.0)
    tool = _tool_point(tool_mm)
    base_joints, base_axes, platform_joints = [], [], []
    for k in range(3):
        angle_deg = first + 120.0 * k
        base_joints.append(circle_point(base_r, angle_deg))
        platform_joints.append(circle_point(platform_r, angle_deg))
        c, s = _cos_sin_deg(angle_deg)
        base_axes.append([-s, c, 0.0])  # the circle's tangent, counter-clockwise
    if name is None:
        name = f"tripod R{base_r:g}/{platform_r:g} mm, height {height:g} mm"
    machine: Dict[str, Any] = {"name": name, "type": "tripod", "angles": angles, "base_joints": base_joints,
                               "base_axes": base_axes, "platform_joints": platform_joints}
    return _finish(machine, tool, height, home, limits, motion, sections)
