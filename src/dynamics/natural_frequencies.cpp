#include "dynamics/natural_frequencies.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/units.hpp"

namespace pkm::dynamics {
namespace {

/// −∂(applied − J_Bᵀ F*)/∂δ at the equilibrium, F* held: central differences along each coordinate.
Result<CoordinateMatrix> geometric_stiffness(const ElasticModel& model, const StaticEquilibrium& e,
                                             const ModalOptions& options) {
  const int m = model.coordinates;
  const double size_mm = model.mechanism->platform_size_mm();
  CoordinateMatrix k(m, m);
  for (int c = 0; c < m; ++c) {
    const bool angular = model.basis.col(c).tail<3>().squaredNorm() > 0.0;
    const double h = options.difference_step_mm / (angular ? size_mm : 1.0);
    CoordinateVector step = CoordinateVector::Zero(m);
    step[c] = h;
    auto plus = rest_generalised_force(model, displaced_pose(model, e.pose, step), e.drive_position_mm, {},
                                       nullptr, &e.strut_force_N);
    auto minus = rest_generalised_force(model, displaced_pose(model, e.pose, -step), e.drive_position_mm, {},
                                        nullptr, &e.strut_force_N);
    if (!plus) return plus.error();
    if (!minus) return minus.error();
    k.col(c) = -(*plus - *minus) / (2.0 * h);
  }
  return k;
}

/// Scales a mode to a largest platform-joint (or tool-point) motion of 1 mm, largest component positive.
void normalise_mode(const ElasticModel& model, const MechanismState& state, double size_mm,
                    Eigen::Ref<CoordinateVector> mode) {
  const Twist d = model.basis * mode;
  double largest = d.head<3>().norm();
  for (int j = 0; j < state.struts; ++j) {
    const Eigen::Vector3d arm = state.ends.platform_mm[j] - state.pose.position_mm;
    largest = std::max(largest, (d.head<3>() + d.tail<3>().cross(arm)).norm());
  }
  if (largest > 0.0) mode /= largest;
  int biggest = 0;
  double biggest_size = -1.0;
  for (int c = 0; c < mode.size(); ++c) {
    const bool angular = model.basis.col(c).tail<3>().squaredNorm() > 0.0;
    const double component = std::abs(mode[c]) * (angular ? size_mm : 1.0);
    if (component > biggest_size) biggest_size = component, biggest = c;
  }
  if (mode[biggest] < 0.0) mode = -mode;
}

}  // namespace

Result<NaturalModes> natural_modes(const ElasticModel& model, const Pose& commanded,
                                   const ModalOptions& options) {
  const Mechanism& mechanism = *model.mechanism;
  auto completed = mechanism.complete_pose(commanded);
  if (!completed) return completed.error();
  ActuatorVector drives(mechanism.actuator_count());
  if (!mechanism.actuator_values(*completed, drives.data())) {
    return make_error(ErrorCode::unreachable, "natural frequencies: the pose is out of reach");
  }
  auto equilibrium = static_equilibrium(model, drives, *completed, {}, options.equilibrium);
  if (!equilibrium) return equilibrium.error();
  NaturalModes modes;
  modes.equilibrium = *equilibrium;
  modes.count = model.coordinates;
  auto equations =
      equations_of_motion(mechanism, *model.parameters, modes.equilibrium.pose, model.basis, Twist::Zero());
  if (!equations) return equations.error();
  modes.mass = equations->mass;
  modes.stiffness = material_stiffness(model, equations->state);
  if (options.geometric_stiffness) {
    auto geometric = geometric_stiffness(model, modes.equilibrium, options);
    if (!geometric) return geometric.error();
    const double scale = modes.stiffness.cwiseAbs().maxCoeff();
    modes.geometric_asymmetry = (*geometric - geometric->transpose()).cwiseAbs().maxCoeff() / scale;
    const CoordinateMatrix symmetric = 0.5 * (*geometric + geometric->transpose());
    modes.stiffness += symmetric;
    modes.geometric_share = symmetric.cwiseAbs().maxCoeff() / modes.stiffness.cwiseAbs().maxCoeff();
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<CoordinateMatrix> solver(modes.stiffness, modes.mass);
  if (solver.info() != Eigen::Success) {
    return make_error(ErrorCode::singular,
                      "natural frequencies: the mass matrix is not positive definite (a massless direction)");
  }
  if (!(solver.eigenvalues()[0] > 0.0)) {
    return make_error(
        ErrorCode::singular,
        fmt::format("natural frequencies: not stable at this pose (ω² = {:.3g} s⁻² in the softest "
                    "direction)",
                    solver.eigenvalues()[0]));
  }
  modes.frequency_Hz = solver.eigenvalues().cwiseSqrt() / (2.0 * kPi);
  modes.shape = solver.eigenvectors();
  const double size_mm = mechanism.platform_size_mm();
  for (int i = 0; i < modes.count; ++i) normalise_mode(model, equations->state, size_mm, modes.shape.col(i));
  return modes;
}

std::vector<double> lowest_frequency_map(const ElasticModel& model, const std::vector<Pose>& poses,
                                         const ModalOptions& options) {
  std::vector<double> lowest;
  lowest.reserve(poses.size());
  for (const Pose& pose : poses) {
    auto modes = natural_modes(model, pose, options);
    lowest.push_back(modes ? modes->frequency_Hz[0] : std::numeric_limits<double>::quiet_NaN());
  }
  return lowest;
}

}  // namespace pkm::dynamics
