#include "stiffness/strut_compliance.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace pkm::stiffness {
namespace {

// Below this ratio of the smallest to the largest pivot of the equilibrated K_T the struts no longer hold the
// platform in some direction: the compliance would be rounding, not a number.
constexpr double kUnboundedRatio = 1e-12;

// At most six allowed coordinates: fixed storage, so a compliance per path point does not allocate.
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

// K⁻¹ for a positive definite K, equilibrated to a unit diagonal first, so that mm and rad coordinates weigh
// alike in the test for a direction the struts do not hold.
template <class Matrix>
Status invert_stiffness(const Matrix& k, Matrix& inverse) {
  using Vector = Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1, 0, 6, 1>;
  const Vector scale = k.diagonal().cwiseMax(0.0).cwiseSqrt().cwiseInverse();
  if (!scale.allFinite()) {
    return make_error(ErrorCode::singular, "unbounded compliance: no strut resists some allowed motion");
  }
  const Matrix equilibrated = scale.asDiagonal() * k * scale.asDiagonal();
  // The pivots of L D Lᵀ bound the smallest eigenvalue of the unit-diagonal matrix from above: one near zero
  // is a direction the struts do not hold (an eigen-solver would say the same at several times the cost).
  const Eigen::LDLT<Matrix> factor(equilibrated);
  const Vector pivots = factor.vectorD();
  if (factor.info() != Eigen::Success || !(pivots.minCoeff() > kUnboundedRatio * pivots.maxCoeff())) {
    return make_error(ErrorCode::singular,
                      "unbounded compliance: the struts cannot hold the platform in some direction here "
                      "(a singular position)");
  }
  inverse = scale.asDiagonal() * factor.solve(Matrix::Identity(k.rows(), k.cols())) * scale.asDiagonal();
  return ok_status();
}

// True when some carriage is compliant: only then is the carriages' motion needed.
bool has_compliant_carriages(const StiffnessParameters& stiffness) {
  for (int j = 0; j < stiffness.strut_count; ++j) {
    const CarriageCompliance& c = stiffness.carriages[j];
    if (c.drive_stiffness_N_mm > 0.0 || c.guide_mm_N > 0.0) return true;
  }
  return false;
}

}  // namespace

double series_compliance_mm_N(const StiffnessParameters& stiffness, int strut, const Eigen::Vector3d& u,
                              const Eigen::Vector3d& carriage_motion) {
  if (stiffness.model == StiffnessModel::struts) return 0.0;
  const JointCompliance& joint = stiffness.joints[strut];
  double compliance = joint.base_mm_N + joint.platform_mm_N;
  const double reach = carriage_motion.norm();
  if (reach > 0.0) {
    const CarriageCompliance& carriage = stiffness.carriages[strut];
    const double along = u.dot(carriage_motion);  // strut-end travel per unit drive value, along the strut
    if (carriage.drive_stiffness_N_mm > 0.0) compliance += along * along / carriage.drive_stiffness_N_mm;
    const double cosine = along / reach;
    compliance += carriage.guide_mm_N * std::max(0.0, 1.0 - cosine * cosine);
  }
  return compliance;
}

Result<StiffnessParameters> strut_stiffness_of(const Machine& machine) {
  if (machine.stiffness.given()) return machine.stiffness;
  const DynamicsParameters& dynamics = machine.dynamics;
  StiffnessParameters from_dynamics;
  from_dynamics.strut_count = dynamics.strut_count;
  from_dynamics.line = dynamics.line;
  bool every = dynamics.given() && dynamics.strut_count == machine.mechanism->actuator_count();
  for (int j = 0; every && j < dynamics.strut_count; ++j) {
    from_dynamics.struts[j].stiffness_N_mm = dynamics.struts[j].stiffness_N_mm;
    every = dynamics.struts[j].stiffness_N_mm > 0.0;
  }
  if (every) return from_dynamics;
  return Error{
      ErrorCode::bad_input,
      fmt::format("{}: stiffness.struts: not given: the machine file has no stiffness: section (and no "
                  "stiffness_N_mm for every strut in dynamics:), docs/machine-file.md",
                  machine.source),
      ErrorLocation{machine.source, 0, 0, "stiffness.struts"}};
}

Result<ToolCompliance> strut_compliance(const Mechanism& mechanism, const StiffnessParameters& stiffness,
                                        const Pose& pose) {
  auto completed = mechanism.complete_pose(pose);
  if (!completed) return completed.error();
  ToolCompliance out;
  out.pose = *completed;
  StrutJointPoints ends;
  const int struts = mechanism.strut_ends(out.pose, ends);
  if (struts < 0) return make_error(ErrorCode::unreachable, "the pose is out of the mechanism's reach");
  if (struts == 0 || struts != stiffness.strut_count) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("the {} has {} struts, the stiffness parameters {}",
                                  to_string(mechanism.type()), struts, stiffness.strut_count));
  }
  auto& lines = out.strut_lines;
  lines.resize(struts, 6);
  out.strut_stiffness_N_mm.resize(struts);
  out.strut_length_mm.resize(struts);
  // The carriages' positions, only when their drives or guides give way (glide machines).
  std::array<double, kMaxActuators> actuators{};
  const bool carriages = stiffness.model != StiffnessModel::struts && has_compliant_carriages(stiffness);
  if (carriages && !mechanism.actuator_values(out.pose, actuators.data()))
    return make_error(ErrorCode::unreachable, "the pose is out of the mechanism's reach");
  for (int j = 0; j < struts; ++j) {
    const Eigen::Vector3d d = ends.platform_mm[j] - ends.base_mm[j];
    const double length = d.norm();
    if (!(length > 0.0))
      return make_error(ErrorCode::singular, fmt::format("strut {} has zero length", j + 1));
    const Eigen::Vector3d u = d / length;
    lines.row(j).head<3>() = u.transpose();
    lines.row(j).tail<3>() = (ends.platform_mm[j] - out.pose.position_mm).cross(u).transpose();
    out.strut_length_mm[j] = length;
    Eigen::Vector3d carriage_motion = Eigen::Vector3d::Zero(), unused;
    if (carriages) mechanism.base_joint_motion(j, actuators[j], carriage_motion, unused);
    const double series = series_compliance_mm_N(stiffness, j, u, carriage_motion);
    out.strut_stiffness_N_mm[j] = 1.0 / (1.0 / stiffness.struts[j].at_length(length) + series);
  }
  // A platform that controls all six coordinates moves freely: its allowed twists are all twists, so no
  // projection (and no angle convention's own singularity in it), and fixed-size 6 × 6 algebra (Eigen's
  // dynamic-size solves go through its blocked kernels, slow at this size).
  out.dof = mechanism.controlled_axes().count();
  if (out.dof == 6) {
    const Matrix6 k = lines.transpose() * out.strut_stiffness_N_mm.asDiagonal() * lines;
    if (Status inverted = invert_stiffness(k, out.compliance); !inverted) return inverted.error();
  } else {
    TwistBasis allowed;
    if (!mechanism.controlled_twists(out.pose, allowed)) {
      return make_error(ErrorCode::singular, "the mechanism's constraints are singular at this pose");
    }
    const SmallMatrix lines_allowed = lines * allowed;  // strut stretch per allowed coordinate
    const SmallMatrix k = lines_allowed.transpose() * out.strut_stiffness_N_mm.asDiagonal() * lines_allowed;
    SmallMatrix inverse;
    if (Status inverted = invert_stiffness(k, inverse); !inverted) return inverted.error();
    out.compliance = allowed * inverse * allowed.transpose();
  }
  out.compliance = 0.5 * (out.compliance + out.compliance.transpose()).eval();
  return out;
}

PrincipalStiffness principal_stiffness(const ToolCompliance& compliance, bool rotational) {
  const int at = rotational ? 3 : 0;
  const Eigen::Matrix3d block = compliance.compliance.block<3, 3>(at, at);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spectrum(block);
  PrincipalStiffness out;
  // Descending compliance = ascending stiffness.
  for (int i = 0; i < 3; ++i) {
    const double c = spectrum.eigenvalues()[2 - i];
    const double largest = spectrum.eigenvalues()[2];
    out.stiffness[i] = c > 1e-12 * largest ? 1.0 / c : std::numeric_limits<double>::infinity();
    out.directions.col(i) = spectrum.eigenvectors().col(2 - i);
  }
  return out;
}

}  // namespace pkm::stiffness
