#pragma once
// The angle between two orientations, kept as its sine and cosine: compared with another angle without an
// arc tangent (the run monitor does it every servo period), and in degrees where it is reported.
#include <Eigen/Core>

namespace pkm {

/// An angle θ ∈ [0, π] as (sin θ, cos θ); NaN where not measured.
struct RotationAngle {
  double sin = 0.0;
  double cos = 1.0;
  double degrees() const;
  /// θ > other.θ: for angles in [0, π] the sign of sin(θ − other.θ); false where either is NaN.
  bool exceeds(const RotationAngle& other) const { return sin * other.cos - cos * other.sin > 0.0; }
  static RotationAngle of_degrees(double angle_deg);
};

/// The angle of the rotation D = a·bᵀ between two rotation matrices, from its trace (1 + 2 cos θ) and its
/// skew part (2 sin θ times the axis): accurate at every angle, small ones included.
RotationAngle rotation_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

}  // namespace pkm
