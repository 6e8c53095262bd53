#pragma once
// The hot inverse kinematics of six struts between base-fixed and platform-fixed joints (the hexapod's):
//   L_j = | p + R·b_j − a_j |,  j = 1 … 6,
// all six at once, the joints stored by coordinate so that each operation works on several struts.
#include <Eigen/Core>

#include "core/pose.hpp"

namespace pkm {

/// Six struts' joints by coordinate: row k holds component k of the six joints.
struct SixStrutLayout {
  Eigen::Matrix<double, 3, 6, Eigen::RowMajor> platform_mm;  ///< b_j, platform joints in the tool frame
  Eigen::Matrix<double, 3, 6, Eigen::RowMajor> base_mm;      ///< a_j, base joints in the base frame
};

/// lengths_mm[j] = |p + R·b_j − a_j| for the six struts of `layout` at `pose`; true when every length is > 0
/// (false: a platform joint on its base joint, or not a number). No allocation; the same bits on every
/// processor (an AVX2 or AVX-512 copy runs where the processor has it, without fused multiply–adds).
bool six_strut_lengths(const SixStrutLayout& layout, const Pose& pose, double* lengths_mm) noexcept;
/// The same with the baseline (SSE2) lanes whatever the processor: for the tests, which compare the two.
bool six_strut_lengths_baseline(const SixStrutLayout& layout, const Pose& pose, double* lengths_mm) noexcept;

}  // namespace pkm
