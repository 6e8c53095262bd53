#pragma once
// One programmed move as a geometric curve: a straight line or a circular helix for the tool point, and a
// spherical-linear (slerp) interpolation of the platform orientation between the move's end rotations.
// Both are parametrised by the fraction f ∈ [0, 1] of the move; `param_length` converts the path parameter s
// into f (s = f · param_length). For moves of the tool point, param_length is the arc length in mm (so ds/dt
// is the tool-point speed, the quantity a feed F programs); for moves that only rotate, it is the rotation
// angle in degrees (a feed then programs degrees per minute, as in LinuxCNC).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pkm::path {

enum class CurveKind { line, helix };

struct Curve {
  CurveKind kind = CurveKind::line;
  Eigen::Vector3d start_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_mm = Eigen::Vector3d::Zero();
  // Helix: p(f) = centre + r(f) (cos(fθ) u + sin(fθ) v) + f·axial·normal, with v = normal × u and r(f)
  // linear.
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double radius_mm = 0.0;      ///< at the start
  double radius_end_mm = 0.0;  ///< at the end: an accepted arc's end may lie slightly off its circle, so the
                               ///< radius changes linearly along the move (a spiral, as LinuxCNC does)
  double sweep_rad = 0.0;      ///< positive: counter-clockwise about `normal`
  double axial_mm = 0.0;       ///< helix advance along `normal` over the whole move
  Eigen::Quaterniond start_rotation = Eigen::Quaterniond::Identity();
  Eigen::Quaterniond end_rotation = Eigen::Quaterniond::Identity();
  double rotation_angle_rad = 0.0;  ///< angle between start and end rotation
  double translation_mm = 0.0;      ///< arc length of the tool point
  double param_length = 0.0;        ///< mm (tool point moves) or deg (rotation-only moves)
  /// Active tool length (G43): the controlled point is the tip plus tool_length·R·tool_axis_platform, so the
  /// tip follows the programmed line or arc while the platform turns (tool-centre-point semantics).
  double tool_length_mm = 0.0;
  Eigen::Vector3d tool_axis_platform = Eigen::Vector3d::UnitZ();

  bool rotation_only() const { return translation_mm <= 1e-9; }
  /// The tool tip at fraction f.
  Eigen::Vector3d tip(double f) const;
  /// The controlled point (tip + tool length along the tool axis) at fraction f.
  Eigen::Vector3d position(double f) const {
    return tool_length_mm == 0.0 ? tip(f) : tip(f) + tool_length_mm * (rotation(f) * tool_axis_platform);
  }
  Eigen::Quaterniond rotation(double f) const;
  /// d tip / d f: exact, so that tangents stay exact on moves of a micrometre (a finite difference of
  /// positions near 700 mm keeps only a few digits there).
  Eigen::Vector3d tip_velocity(double f) const;
  /// d position / d f, the controlled point's: the tip's, plus the tool turning with the platform.
  Eigen::Vector3d velocity(double f) const;
  /// The platform's angular velocity per unit f in the base frame (constant along a slerp).
  Eigen::Vector3d angular_rate() const;
};

Curve make_line(const Eigen::Vector3d& start_mm, const Eigen::Vector3d& end_mm, const Eigen::Quaterniond& q0,
                const Eigen::Quaterniond& q1);
/// A circular arc or helix from `start_mm` to `end_mm` about `centre_mm` (any point on the axis), turning
/// counter-clockwise about the unit `normal`, `turns` ≥ 1 as in G2/G3 P.
Curve make_helix(const Eigen::Vector3d& start_mm, const Eigen::Vector3d& end_mm,
                 const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& normal, int turns,
                 const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1);

/// Slerp that takes the short way and stays exact at both ends.
Eigen::Quaterniond slerp_short(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double w);

}  // namespace pkm::path
