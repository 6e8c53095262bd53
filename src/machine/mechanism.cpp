#include "machine/mechanism.hpp"

#include <fmt/format.h>

#include "core/rotation.hpp"

namespace pkm {

std::string_view to_string(MechanismType type) {
  switch (type) {
    case MechanismType::planar2:
      return "planar2";
    case MechanismType::planar3:
      return "planar3";
    case MechanismType::hexapod:
      return "hexapod";
    case MechanismType::hexapod_refined:
      return "hexapod_refined";
    case MechanismType::tripod:
      return "tripod";
    case MechanismType::tricept:
      return "tricept";
    case MechanismType::glide:
      return "glide";
    case MechanismType::rotopod:
      return "rotopod";
  }
  return "?";
}

std::optional<MechanismType> mechanism_type_from_string(std::string_view name) {
  for (MechanismType t : {MechanismType::planar2, MechanismType::planar3, MechanismType::hexapod,
                          MechanismType::hexapod_refined, MechanismType::tripod, MechanismType::tricept,
                          MechanismType::glide, MechanismType::rotopod}) {
    if (to_string(t) == name) return t;
  }
  return std::nullopt;
}

Result<std::vector<FkSolution>> Mechanism::forward_all(const ActuatorVector&, const FkOptions&) const {
  return make_error(
      ErrorCode::unsupported,
      fmt::format("{} mechanisms do not enumerate assembly modes; solve from a guess pose instead",
                  to_string(type())));
}

Result<AssemblyModes> Mechanism::assembly_modes(const ActuatorVector& actuators,
                                                const FkOptions& options) const {
  auto solutions = forward_all(actuators, options);
  if (!solutions) return solutions.error();
  AssemblyModes modes;
  modes.report.method = "enumeration";
  modes.report.real = static_cast<int>(solutions->size());
  modes.solutions = std::move(*solutions);
  return modes;
}

bool Mechanism::forward_warm_quiet(const ActuatorVector& actuators, const Pose& guess,
                                   const FkOptions& options, FkWorkspace& workspace, FkSolution& out,
                                   ErrorCode& failure) const {
  auto solution = forward_warm(actuators, guess, options, workspace);
  if (!solution) {
    failure = solution.error().code;
    return false;
  }
  out = solution.value();
  return true;
}

Result<FkSolution> Mechanism::forward_warm(const ActuatorVector& actuators, const Pose& guess,
                                           const FkOptions& options, FkWorkspace& /*workspace*/) const {
  return forward(actuators, guess, options);
}

std::unique_ptr<FkWorkspace> Mechanism::make_fk_workspace() const {
  return std::make_unique<FkWorkspace>(this);
}

bool Mechanism::actuator_values(const Pose& pose, double* out) const noexcept {
  auto values = inverse(pose);
  if (!values) return false;
  for (int j = 0; j < values->size(); ++j) out[j] = (*values)[j];
  return true;
}

bool Mechanism::actuator_values_at(AngleConvention convention, const PoseVector& coordinates,
                                   double* out) const noexcept {
  return actuator_values(pose_from_vector(convention, coordinates), out);
}

Eigen::Matrix<double, 6, 6> coordinate_twists(AngleConvention convention, const Pose& pose) noexcept {
  Eigen::Matrix<double, 6, 6> t = Eigen::Matrix<double, 6, 6>::Zero();
  t.topLeftCorner<3, 3>().setIdentity();
  t.bottomRightCorner<3, 3>() =
      angular_velocity_matrix(convention, angles_from_rotation(convention, pose.rotation));
  return t;
}

bool Mechanism::controlled_twists(const Pose& pose, TwistBasis& out) const noexcept {
  const Eigen::Matrix<double, 6, 6> all = coordinate_twists(convention(), pose);
  const AxisMask mask = controlled_axes();
  out.resize(6, mask.count());
  int column = 0;
  for (int axis = 0; axis < 6; ++axis) {
    if (mask.controlled[axis]) out.col(column++) = all.col(axis);
  }
  return true;
}

bool Mechanism::twist_jacobian(const Pose& /*pose*/, JacobianMatrix& /*out*/) const noexcept {
  return false;
}

int Mechanism::strut_state(const Pose& pose, StrutJointPoints& ends, double* actuators,
                           JacobianMatrix& twist_rows) const noexcept {
  const int struts = strut_ends(pose, ends);
  if (struts < 0 || !actuator_values(pose, actuators) || !twist_jacobian(pose, twist_rows)) return -1;
  return struts;
}

double Mechanism::platform_size_mm() const {
  StrutJointPoints joints;
  const Pose& at = home();
  const int count = strut_joints(at, joints);
  double sum_mm = 0.0;
  for (int j = 0; j < count; ++j) sum_mm += (joints.platform_mm[j] - at.position_mm).norm();
  // Without platform joints: the order of size of a machine-tool platform.
  constexpr double kUnknownPlatformSizeMm = 100.0;
  return sum_mm > 0.0 ? sum_mm / count : kUnknownPlatformSizeMm;
}

bool strut_length_twist_jacobian(const StrutJointPoints& joints, int count,
                                 const Eigen::Vector3d& tool_point_mm, JacobianMatrix& out) noexcept {
  out.resize(count, 6);
  for (int j = 0; j < count; ++j) {
    const Eigen::Vector3d strut = joints.platform_mm[j] - joints.base_mm[j];
    const double length_mm = strut.norm();
    if (!(length_mm > 0.0)) return false;
    const Eigen::Vector3d unit = strut / length_mm;
    out.block<1, 3>(j, 0) = unit.transpose();
    out.block<1, 3>(j, 3) = (joints.platform_mm[j] - tool_point_mm).cross(unit).transpose();
  }
  return true;
}

Error another_assembly_mode_error(const Pose& solution) {
  const Eigen::Vector3d& p = solution.position_mm;
  return make_error(ErrorCode::wrong_branch,
                    fmt::format("forward kinematics converged to another assembly mode than the guess's "
                                "(x={:.3f} y={:.3f} z={:.3f} mm); give a guess nearer the wanted pose",
                                p.x(), p.y(), p.z()));
}

std::array<std::string, 6> pose_coordinate_names(const Mechanism& mechanism) {
  if (mechanism.is_planar()) {
    return {"x", "y", "z", "-", "-", "phi"};
  }
  switch (mechanism.convention()) {
    case AngleConvention::abc:
      return {"x", "y", "z", "A", "B", "C"};
    case AngleConvention::krylov:
      return {"x", "y", "z", "psi", "theta", "gamma"};
    case AngleConvention::euler_zxz:
      return {"x", "y", "z", "psi", "theta", "phi"};
  }
  return {"x", "y", "z", "a1", "a2", "a3"};
}

std::vector<std::string> controlled_coordinate_names(const Mechanism& mechanism) {
  const auto names = pose_coordinate_names(mechanism);
  const AxisMask mask = mechanism.controlled_axes();
  std::vector<std::string> out;
  for (int i = 0; i < 6; ++i) {
    if (mask.controlled[i]) out.push_back(names[i]);
  }
  return out;
}

}  // namespace pkm

namespace pkm {

Result<std::unique_ptr<Mechanism>> Mechanism::with_geometry(
    const std::vector<GeometryGroup>& /*groups*/) const {
  return make_error(ErrorCode::unsupported,
                    fmt::format("a {} has no geometric parameters to calibrate", to_string(type())));
}

Status check_geometry_groups(const std::vector<GeometryGroup>& expected,
                             const std::vector<GeometryGroup>& groups) {
  if (groups.size() != expected.size()) {
    return make_error(ErrorCode::bad_input, fmt::format("{} geometry groups given where the mechanism has {}",
                                                        groups.size(), expected.size()));
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto& want = expected[g];
    const auto& got = groups[g];
    if (got.key != want.key || got.rows != want.rows || got.columns() != want.columns() ||
        got.values.size() != want.values.size()) {
      return make_error(
          ErrorCode::bad_input,
          fmt::format("geometry group {} is '{}' ({} × {}) where '{}' ({} × {}) is expected", g + 1, got.key,
                      got.rows, got.columns(), want.key, want.rows, want.columns()));
    }
    for (double v : got.values) {
      if (!std::isfinite(v)) {
        return make_error(ErrorCode::bad_input,
                          fmt::format("geometry group '{}' has a value that is not finite", got.key));
      }
    }
  }
  return ok_status();
}

Eigen::Vector3d group_point(const GeometryGroup& group, int row) {
  const auto* v = group.values.data() + static_cast<std::size_t>(row) * 3;
  return {v[0], v[1], v[2]};
}

GeometryGroup point_group(std::string key, std::string row_symbol, const Eigen::Vector3d* points, int count) {
  GeometryGroup group{std::move(key), std::move(row_symbol), {"x", "y", "z"}, "mm", count, {}};
  group.values.reserve(static_cast<std::size_t>(count) * 3);
  for (int i = 0; i < count; ++i)
    group.values.insert(group.values.end(), {points[i].x(), points[i].y(), points[i].z()});
  return group;
}

}  // namespace pkm
