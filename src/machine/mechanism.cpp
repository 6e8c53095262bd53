#include "machine/mechanism.hpp"

#include <fmt/format.h>

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
      fmt::format("{} mechanisms do not enumerate assembly modes; give --guess instead of --all",
                  to_string(type())));
}

Error another_assembly_mode_error(const Pose& solution) {
  const Eigen::Vector3d& p = solution.position_mm;
  return make_error(ErrorCode::wrong_branch,
                    fmt::format("forward kinematics converged to another assembly mode than the guess's "
                                "(x={:.3f} y={:.3f} z={:.3f} mm); give a guess nearer the wanted pose",
                                p.x(), p.y(), p.z()));
}

std::array<std::string, 6> pose_coordinate_names(const Mechanism& mechanism) {
  if (mechanism.type() == MechanismType::planar2 || mechanism.type() == MechanismType::planar3) {
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
