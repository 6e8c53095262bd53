#pragma once
// The copies behind rotation_from_angles (core/rotation.hpp), for the tests that compare them: the hot path
// takes an AVX2 copy where the processor has it, which must give the same bits as the baseline one.
#include <Eigen/Core>

#include "core/rotation.hpp"

namespace pkm {

/// rotation_from_angles without the AVX2 copy, whatever the processor.
Eigen::Matrix3d rotation_from_angles_baseline(AngleConvention convention, const Eigen::Vector3d& angles_rad);

}  // namespace pkm
