#pragma once
// Three-sphere intersection ("three hinged rods meeting at one point", Smirnov §2.3.3): the point B with
// |B − A_j| = L_j for three centres A_j. Two forms:
//   * classical, in any frame: subtracting the sphere equations gives two linear equations, which leave a
//   line
//     normal to the centre plane; the first sphere then gives a quadratic along that line (§4.6(a)
//     recommendation);
//   * the dissertation's quaternion form (56)–(59), for centres in one horizontal plane (z_A1 = z_A2 = z_A3),
//     keeping the intermediate values a11…b2, λ01, λ02, λ0 so they can be checked.
// Both give two mirror-image points, one on each side of the centre plane. Fixed-size results, no allocation.
#include <Eigen/Core>
#include <array>

namespace pkm {

enum class TrilaterationStatus {
  two_points,          ///< the spheres meet in two mirror-image points
  one_point,           ///< the spheres touch: both points coincide in the centre plane
  infeasible_lengths,  ///< the spheres do not meet (or a length is not positive)
  collinear_centres,   ///< the three centres lie on one line: the intersection is a circle, not points
  centres_not_level,   ///< quaternion form only: the centres do not share one z
};

const char* to_string(TrilaterationStatus status);

struct SphereIntersection {
  TrilaterationStatus status = TrilaterationStatus::infeasible_lengths;
  int count = 0;                                     ///< 0, 1 or 2 points
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit normal of the centre plane, (A2−A1)×(A3−A1)
  Eigen::Vector3d above_mm = Eigen::Vector3d::Zero();  ///< point on the +normal side (or the single point)
  Eigen::Vector3d below_mm = Eigen::Vector3d::Zero();  ///< mirror point on the −normal side
  double height_mm = 0.0;                              ///< distance of both points from the centre plane
};

/// Classical trilateration in a general frame. `touch_tolerance_mm`: a height below it counts as one point.
SphereIntersection intersect_three_spheres(const std::array<Eigen::Vector3d, 3>& centres_mm,
                                           const std::array<double, 3>& radii_mm,
                                           double touch_tolerance_mm = 1e-9);

/// One root of (57): the rotation Λ_A2 = λ0 + i1 λ1 + i2 λ2 (λ3 = 0) of rod 2 from vertical, and B from (59).
struct QuaternionRoot {
  double lambda0 = 0.0;  ///< chosen ≥ 0 (Λ and −Λ are the same rotation)
  double lambda1 = 0.0;
  double lambda2 = 0.0;
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
};

struct QuaternionTrilateration {
  TrilaterationStatus status = TrilaterationStatus::infeasible_lengths;
  int count = 0;
  double a11 = 0.0, a12 = 0.0, a21 = 0.0, a22 = 0.0;  ///< (56) coefficients
  double b1 = 0.0, b2 = 0.0;                          ///< (56) right-hand sides
  double lambda01 = 0.0;                              ///< λ0·λ1 of Λ_A2, from (56)
  double lambda02 = 0.0;                              ///< λ0·λ2 of Λ_A2, from (56)
  QuaternionRoot plus;                                ///< '+' root of (57): B above the joint plane
  QuaternionRoot minus;                               ///< '−' root of (57): the mirror image below it
};

/// The quaternion algorithm (56)–(59). The centres must share one z (within `level_tolerance_mm`).
QuaternionTrilateration quaternion_trilateration(const std::array<Eigen::Vector3d, 3>& centres_mm,
                                                 const std::array<double, 3>& lengths_mm,
                                                 double level_tolerance_mm = 1e-9);

}  // namespace pkm
