// Machine-file entry of the hexapod: base_joints (6 points, base frame) and platform_joints (6 points,
// platform frame); `tool` shifts the pose origin to the tool point.
#include "io/mechanism_files.hpp"
#include "machine/hexapod.hpp"

namespace pkm {

Result<HexapodFileGeometry> read_hexapod_geometry(const MechanismSpec& spec) {
  auto base = spec.reader.points(spec.root, "base_joints", 6, 3);
  if (!base) return base.error();
  auto platform = spec.reader.points(spec.root, "platform_joints", 6, 3);
  if (!platform) return platform.error();
  HexapodFileGeometry out;
  std::vector<Eigen::Vector3d> platform_tool;
  for (int j = 0; j < 6; ++j) {
    out.geometry.base_joints_mm[j] = (*base)[j];
    out.geometry.platform_joints_mm[j] = (*platform)[j] - spec.tool_mm;
    platform_tool.push_back(out.geometry.platform_joints_mm[j]);
  }
  PoseVector home = PoseVector::Zero();
  if (spec.home) {
    home = *spec.home;
  } else {
    home[2] = default_home_height_mm(*base, platform_tool, spec.limits);
  }
  out.home = pose_from_vector(spec.convention, home);
  return out;
}

MechanismFileEntry hexapod_file_entry() {
  return {MechanismType::hexapod,
          {"base_joints", "platform_joints"},
          6,
          [](const MechanismSpec& spec) -> Result<std::unique_ptr<Mechanism>> {
            auto read = read_hexapod_geometry(spec);
            if (!read) return read.error();
            auto hexapod = std::make_unique<Hexapod>(read->geometry, spec.convention, read->home);
            // A singular home would make every FK from it ill-posed.
            const double det = hexapod->twist_jacobian(hexapod->home()).determinant();
            if (!(std::abs(det) > 1e-9)) {
              const YAML::Node where = spec.root["home"] ? spec.root["home"] : spec.root["platform_joints"];
              return spec.reader.error_at(where, "home",
                                          "the hexapod is singular at its home pose (det J = 0)");
            }
            return std::unique_ptr<Mechanism>(std::move(hexapod));
          }};
}

}  // namespace pkm
