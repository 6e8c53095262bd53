#include "dynamics/elastic_equilibrium.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "core/rotation.hpp"

namespace pkm::dynamics {
namespace {

/// The largest platform-joint (or tool-point) motion of a displacement, mm: the size a step is judged by.
double largest_joint_motion_mm(const ElasticModel& model, const MechanismState& state,
                               const CoordinateVector& displacement) {
  const Twist d = model.basis * displacement;
  double largest = d.head<3>().norm();
  for (int j = 0; j < state.struts; ++j) {
    const Eigen::Vector3d arm = state.ends.platform_mm[j] - state.pose.position_mm;
    largest = std::max(largest, (d.head<3>() + d.tail<3>().cross(arm)).norm());
  }
  return largest;
}

}  // namespace

Pose displaced_pose(const ElasticModel& model, const Pose& pose, const CoordinateVector& displacement) {
  const Twist d = model.basis * displacement;
  Pose moved = pose;
  moved.position_mm += d.head<3>();
  moved.rotation = rotation_from_rotation_vector(d.tail<3>()) * pose.rotation;
  return moved;
}

CoordinateVector pose_displacement(const ElasticModel& model, const Pose& from, const Pose& to) {
  Twist d;
  d << to.position_mm - from.position_mm,
      rotation_vector_from_rotation(to.rotation * from.rotation.transpose());
  // The basis' columns are orthonormal unit twists (platform_twist_basis): Bᵀ picks the coordinates.
  return model.basis.transpose() * d;
}

Result<CoordinateVector> rest_generalised_force(const ElasticModel& model, const Pose& pose,
                                                const ActuatorVector& drive_position_mm,
                                                const statics::Wrench& load, ActuatorVector* strut_force_N,
                                                const ActuatorVector* fixed_strut_force_N) {
  MechanismState state;
  if (Status s = free_platform_state(model, pose, state); !s) return s.error();
  RigidTerms rigid;
  rigid_terms(state, *model.parameters, model.basis, Twist::Zero(), load, rigid);
  const int n = model.struts;
  ActuatorVector force_N(n);
  for (int j = 0; j < n; ++j) {
    force_N[j] = fixed_strut_force_N ? (*fixed_strut_force_N)[j]
                                     : model.parameters->struts[j].stiffness_N_mm *
                                           (state.actuators[j] - drive_position_mm[j]);
  }
  if (strut_force_N) *strut_force_N = force_N;
  const JacobianMatrix drive_jacobian = state.twist_jacobian * model.basis;
  return CoordinateVector(rigid.applied - drive_jacobian.transpose() * (force_N * kKgMmS2PerN));
}

Result<StaticEquilibrium> static_equilibrium(const ElasticModel& model,
                                             const ActuatorVector& drive_position_mm, const Pose& guess,
                                             const statics::Wrench& load, const EquilibriumOptions& options) {
  StaticEquilibrium e;
  e.pose = guess;
  e.drive_position_mm = drive_position_mm;
  for (e.iterations = 0; e.iterations < options.max_iterations; ++e.iterations) {
    MechanismState state;
    if (Status s = free_platform_state(model, e.pose, state); !s) return s.error();
    auto force = rest_generalised_force(model, e.pose, drive_position_mm, load, &e.strut_force_N);
    if (!force) return force.error();
    RigidTerms rigid;
    rigid_terms(state, *model.parameters, model.basis, Twist::Zero(), load, rigid);
    const double scale = std::max(rigid.applied.cwiseAbs().maxCoeff(), 1e-300);
    e.residual = force->cwiseAbs().maxCoeff() / scale;
    const Eigen::LLT<CoordinateMatrix> stiffness(material_stiffness(model, state));
    if (stiffness.info() != Eigen::Success) {
      return make_error(ErrorCode::singular,
                        "elastic equilibrium: the struts' stiffness does not hold every platform direction "
                        "(a singular pose)");
    }
    const CoordinateVector step = stiffness.solve(*force);
    e.pose = displaced_pose(model, e.pose, step);
    if (largest_joint_motion_mm(model, state, step) <= options.step_tolerance_mm) {
      ++e.iterations;
      // The forces and the residual where it stopped.
      auto final_force = rest_generalised_force(model, e.pose, drive_position_mm, load, &e.strut_force_N);
      if (!final_force) return final_force.error();
      e.residual = final_force->cwiseAbs().maxCoeff() / scale;
      return e;
    }
  }
  return make_error(
      ErrorCode::not_converged,
      fmt::format("elastic equilibrium: not converged in {} iterations (relative residual {:.3g}): "
                  "the struts are too soft to carry the platform",
                  options.max_iterations, e.residual));
}

}  // namespace pkm::dynamics
