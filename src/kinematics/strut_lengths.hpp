#pragma once
// The hot inverse kinematics of six struts between base-fixed and platform-fixed joints (the hexapod's):
//   L_j = | p + R·b_j − a_j |,  j = 1 … 6,
// all six at once, the joints stored by coordinate so that each operation works on several struts.
#include <Eigen/Core>

#include "core/pose.hpp"

namespace pkm {

/// Six struts' joints by coordinate: row k holds component k of the six joints in columns 0–5. Columns 6 and
/// 7 stay zero: a row fills one AVX-512 vector, loaded whole (a cache line: the rows are 64-byte aligned).
struct SixStrutLayout {
  using Rows = Eigen::Matrix<double, 3, 8, Eigen::RowMajor | Eigen::DontAlign>;
  alignas(64) Rows platform_mm = Rows::Zero();  ///< b_j, platform joints in the tool frame
  alignas(64) Rows base_mm = Rows::Zero();      ///< a_j, base joints in the base frame
};

/// lengths_mm[j] = |p + R·b_j − a_j| for the six struts of `layout` at `pose`; true when every length is > 0
/// (false: a platform joint on its base joint, or not a number). No allocation; the same bits on every
/// processor (an AVX2 or AVX-512 copy runs where the processor has it, without fused multiply–adds).
bool six_strut_lengths(const SixStrutLayout& layout, const Pose& pose, double* lengths_mm) noexcept;
/// The same with the baseline (SSE2) lanes whatever the processor: for the tests, which compare the two.
bool six_strut_lengths_baseline(const SixStrutLayout& layout, const Pose& pose, double* lengths_mm) noexcept;

/// six_strut_lengths at the pose of six coordinates (x, y, z in mm, three angles in rad in `convention`): the
/// hexapod's hot IK from what a controller hands over. The platform joints are turned by the convention's
/// three elementary rotations in turn (core/rotate_by_angles.hpp), the matrix never formed: fewer operations,
/// and the lengths of six_strut_lengths(layout, pose_from_vector(convention, coordinates)) to rounding (a few
/// units in the last place), not their bits. Where the processor has AVX2 or AVX-512, one kernel from the
/// coordinates to the lengths; every copy gives the same bits.
bool six_strut_lengths_at(const SixStrutLayout& layout, AngleConvention convention,
                          const PoseVector& coordinates, double* lengths_mm) noexcept;

/// For the tests, which compare the copies: how many this processor runs (1: the baseline, 2: also AVX2,
/// 3: also AVX-512), and six_strut_lengths_at with copy `kernel` (0, 1, 2: baseline, AVX2, AVX-512; below
/// strut_kernel_count()).
int strut_kernel_count() noexcept;
bool six_strut_lengths_at_kernel(int kernel, const SixStrutLayout& layout, AngleConvention convention,
                                 const PoseVector& coordinates, double* lengths_mm) noexcept;

}  // namespace pkm
