#include "machine/conditioning.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

namespace pkm {

Result<JacobianMeasures> jacobian_measures(const Mechanism& mechanism, const Pose& pose) {
  auto j = mechanism.jacobian(pose);
  if (!j) return j.error();
  JacobianMeasures m;
  const Eigen::JacobiSVD<JacobianMatrix> svd(*j);
  const auto& sv = svd.singularValues();
  // Singular values come sorted, largest first; an empty Jacobian has none (and GCC must see that case).
  if (sv.size() == 0) return make_error(ErrorCode::singular, "the Jacobian is empty at this pose");
  m.min_singular_value = sv.minCoeff();
  m.condition_number = m.min_singular_value > 0 ? sv.maxCoeff() / m.min_singular_value : INFINITY;
  if (j->rows() != j->cols()) return m;
  m.determinant = j->determinant();
  const Eigen::FullPivLU<JacobianMatrix> lu(*j);
  if (!lu.isInvertible()) {
    return make_error(ErrorCode::singular, "the Jacobian is singular at this pose");
  }
  const JacobianMatrix inverse = lu.inverse();  // rows: controlled coordinates, columns: actuators
  const AxisMask mask = mechanism.controlled_axes();
  int row = 0;
  for (int axis = 0; axis < 6; ++axis) {
    if (!mask.controlled[axis]) continue;
    if (axis < 3) m.sensitivity_sums[axis] = inverse.row(row).cwiseAbs().sum();
    ++row;
  }
  m.error_amplification = m.sensitivity_sums.norm();
  return m;
}

WorkspaceSummary sample_workspace(const Machine& machine, const WorkspaceBox& box) {
  const Mechanism& mech = *machine.mechanism;
  const AxisMask mask = mech.controlled_axes();
  const int n = mech.actuator_count();
  const int dims = mask.count();
  WorkspaceSummary s;
  s.actuator_min = ActuatorVector::Constant(n, INFINITY);
  s.actuator_max = ActuatorVector::Constant(n, -INFINITY);
  s.error_amplification_min = INFINITY;
  const PoseVector centre = vector_from_pose(mech.convention(), box.centre);
  int total = 1;
  for (int d = 0; d < dims; ++d) total *= box.samples_per_axis;
  double first_det_sign = 0.0;
  for (int index = 0; index < total; ++index) {
    PoseVector c = centre;
    int rest = index;
    for (int axis = 0; axis < 6; ++axis) {
      if (!mask.controlled[axis]) continue;
      const int k = rest % box.samples_per_axis;
      rest /= box.samples_per_axis;
      const double t = box.samples_per_axis > 1 ? -1.0 + 2.0 * k / (box.samples_per_axis - 1) : 0.0;
      c[axis] += t * (axis < 3 ? box.translation_half_range_mm : box.angle_half_range_rad);
    }
    ++s.poses;
    auto pose = mech.complete_pose(pose_from_vector(mech.convention(), c));
    if (!pose) {
      ++s.unreachable;
      continue;
    }
    auto q = mech.inverse(*pose);
    if (!q) {
      ++s.unreachable;
      continue;
    }
    s.actuator_min = s.actuator_min.cwiseMin(*q);
    s.actuator_max = s.actuator_max.cwiseMax(*q);
    if (!check_actuator_range(machine, *q)) ++s.out_of_range;
    auto m = jacobian_measures(mech, *pose);
    if (!m) {
      ++s.singular;
      continue;
    }
    s.error_amplification_min = std::fmin(s.error_amplification_min, m->error_amplification);
    s.error_amplification_max = std::fmax(s.error_amplification_max, m->error_amplification);
    s.condition_max = std::fmax(s.condition_max, m->condition_number);
    const double sign = m->determinant > 0 ? 1.0 : (m->determinant < 0 ? -1.0 : 0.0);
    if (first_det_sign == 0.0) first_det_sign = sign;
    if (sign != 0.0 && sign != first_det_sign) s.determinant_changes_sign = true;
  }
  return s;
}

}  // namespace pkm
