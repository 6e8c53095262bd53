#pragma once
// The "Simple Matrix Scenario" rotation of Rusanov et al.: the smallest rotation that turns the
// previous tool normal n_old onto the new one n_new, as the Rodrigues matrix written out entry by entry, with
// the printed errors corrected:
//  - entry (1,2) is v_x v_y (1 − cos φ) − v_z sin φ (printed: v_z² sin φ, which is not even orthogonal);
//  - the axis is v = n_old × n_new / |n_old × n_new| (printed: n_p × n_old, about which a turn by +φ takes
//    n_old the other way, away from n_p, onto n_p's mirror image about n_old), cos φ = n_old · n_new.
// The spin about the tool axis this leaves to drift along a path is a redundant coordinate (Smirnov 2019).
#include <Eigen/Core>

namespace pkm {

/// Rotation by `angle_rad` about the unit `axis`, the Rodrigues matrix entry by entry:
///   R = cos φ I + sin φ [v]× + (1 − cos φ) v vᵀ.
Eigen::Matrix3d rodrigues_matrix(const Eigen::Vector3d& axis, double angle_rad);

/// The smallest rotation mapping the unit vector `n_old` onto the unit vector `n_new`: the identity when they
/// are equal, and a half turn about some axis square to them when they are opposite.
Eigen::Matrix3d rotation_between(const Eigen::Vector3d& n_old, const Eigen::Vector3d& n_new);

}  // namespace pkm
