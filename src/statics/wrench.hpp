#pragma once
// A wrench acting on the platform: the resultant force and its moment about one point, both in the base
// frame. Statics (Smirnov (73), (91)) balances it with the strut forces; pkm takes the moment about the tool
// point (the pose origin) rather than Smirnov's base origin O, so that a load written at the tool does not
// change when the machine moves (either point is valid if used consistently).
#include <Eigen/Core>

namespace pkm::statics {

/// Force and moment acting ON the platform, base frame; the moment is about the tool point
/// (Pose::position_mm) unless a function says otherwise.
struct Wrench {
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment_Nmm = Eigen::Vector3d::Zero();
};

/// The same load with its moment taken about `to_point_mm` instead of `from_point_mm` (base frame):
///   M_to = M_from + (from − to) × F.
Wrench shift_wrench(const Wrench& wrench, const Eigen::Vector3d& from_point_mm,
                    const Eigen::Vector3d& to_point_mm);

/// Component-wise sum (moments must be about the same point).
Wrench operator+(const Wrench& a, const Wrench& b);

}  // namespace pkm::statics
