// Machine-file entry of the tricept: base_joints (3 universal-joint centres, base frame), platform_joints (3
// flange joints in the flange frame, origin C on the manipulator axis, z' along the axis away from O),
// optional center_joint (the central cardan point O, default [0, 0, 0]) and optional `tool` (on the axis: [0,
// 0, t]). The pose origin is the tool point. `home:` takes 6 numbers; only x, y, z are used, the angles are
// recomputed.
#include <fmt/format.h>

#include <cmath>

#include "io/mechanism_files.hpp"
#include "machine/tricept.hpp"

namespace pkm {

MechanismFileEntry tricept_file_entry() {
  return {MechanismType::tricept,
          {"base_joints", "platform_joints", "center_joint"},
          6,
          [](const MechanismSpec& spec) -> Result<std::unique_ptr<Mechanism>> {
            auto base = spec.reader.points(spec.root, "base_joints", 3, 3);
            if (!base) return base.error();
            auto platform = spec.reader.points(spec.root, "platform_joints", 3, 3);
            if (!platform) return platform.error();
            TriceptGeometry geometry;
            if (spec.root["center_joint"]) {
              auto center = spec.reader.point(spec.root["center_joint"], "center_joint", 3);
              if (!center) return center.error();
              geometry.center_joint_mm = *center;
            }
            // The cardan forbids rotation about the manipulator axis, so only a tool on that axis keeps the
            // pose a function of the tool point alone.
            if (spec.tool_mm.x() != 0.0 || spec.tool_mm.y() != 0.0) {
              return spec.reader.error_at(
                  spec.root["tool"], "tool",
                  "a tricept's tool must lie on the manipulator axis: [0, 0, t] in the "
                  "flange frame");
            }
            geometry.tool_offset_mm = spec.tool_mm.z();
            std::vector<Eigen::Vector3d> platform_tool, base_shifted;
            const Eigen::Vector3d o_xy(geometry.center_joint_mm.x(), geometry.center_joint_mm.y(), 0.0);
            for (int j = 0; j < 3; ++j) {
              geometry.base_joints_mm[j] = (*base)[j];
              geometry.platform_joints_mm[j] = (*platform)[j];
              platform_tool.push_back((*platform)[j] - spec.tool_mm);
              base_shifted.push_back((*base)[j] - o_xy);
            }
            const Eigen::Vector3d u = (*platform)[1] - (*platform)[0], v = (*platform)[2] - (*platform)[0];
            if (!(u.cross(v).squaredNorm() > 1e-12 * u.squaredNorm() * v.squaredNorm())) {
              return spec.reader.error_at(spec.root["platform_joints"], "platform_joints",
                                          "the three joints are collinear");
            }

            // Default home: the axis vertical above O, mean strut length mid-range.
            Eigen::Vector3d home = o_xy;
            if (spec.home) {
              home = spec.home->head<3>();
            } else {
              home.z() = default_home_height_mm(base_shifted, platform_tool, spec.limits);
            }
            auto tricept = Tricept::create(geometry, spec.convention, home);
            if (!tricept) {
              const YAML::Node where = spec.root["home"] ? spec.root["home"] : spec.root["platform_joints"];
              return spec.reader.error_at(where, "home", tricept.error().message);
            }
            return std::unique_ptr<Mechanism>(std::make_unique<Tricept>(std::move(tricept.value())));
          }};
}

}  // namespace pkm
