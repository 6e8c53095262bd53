// Machine-file entry of the 3-RPS tripod: base_joints (3 points, base frame), base_axes (3 horizontal
// revolute axis directions, base frame, eq. 31) and platform_joints (3 points, platform frame); `tool` shifts
// the pose origin to the tool point. `home:` takes 6 numbers; x, y and the yaw are recomputed from z and the
// tilts (the given yaw only picks the yaw branch of (31)).
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>

#include "io/mechanism_files.hpp"
#include "machine/tripod.hpp"

namespace pkm {
namespace {

bool collinear(const std::vector<Eigen::Vector3d>& p) {
  const Eigen::Vector3d u = p[1] - p[0], v = p[2] - p[0];
  return !(u.cross(v).squaredNorm() > 1e-12 * u.squaredNorm() * v.squaredNorm()) || u.isZero() || v.isZero();
}

}  // namespace

MechanismFileEntry tripod_file_entry() {
  return {
      MechanismType::tripod,
      {"base_joints", "base_axes", "platform_joints"},
      6,
      [](const MechanismSpec& spec) -> Result<std::unique_ptr<Mechanism>> {
        if (spec.convention == AngleConvention::euler_zxz) {
          return spec.reader.error_at(spec.root["angles"], "angles",
                                      "a tripod needs abc or krylov: its controlled tilts must be separable "
                                      "from the rotation about z, which euler_zxz angles are not");
        }
        auto base = spec.reader.points(spec.root, "base_joints", 3, 3);
        if (!base) return base.error();
        auto axes = spec.reader.points(spec.root, "base_axes", 3, 3);
        if (!axes) return axes.error();
        auto platform = spec.reader.points(spec.root, "platform_joints", 3, 3);
        if (!platform) return platform.error();

        TripodGeometry geometry;
        std::vector<Eigen::Vector3d> platform_tool;
        for (int j = 0; j < 3; ++j) {
          const Eigen::Vector3d& a = (*axes)[j];
          const YAML::Node node = spec.root["base_axes"][j];
          const std::string key = fmt::format("base_axes[{}]", j);
          if (!(a.norm() > 0.0))
            return spec.reader.error_at(node, key, "the axis direction must not be zero");
          if (std::abs(a.z()) > 1e-9 * a.norm()) {
            return spec.reader.error_at(node, key,
                                        "the revolute axis must be horizontal (z = 0, eq. 31), so that each "
                                        "strut moves in a vertical plane");
          }
          geometry.base_joints_mm[j] = (*base)[j];
          geometry.base_axes[j] = a.normalized();
          geometry.platform_joints_mm[j] = (*platform)[j] - spec.tool_mm;
          platform_tool.push_back(geometry.platform_joints_mm[j]);
        }
        const Eigen::Vector3d first = geometry.base_axes[0];
        if (std::abs(first.cross(geometry.base_axes[1]).z()) < 1e-9 &&
            std::abs(first.cross(geometry.base_axes[2]).z()) < 1e-9) {
          return spec.reader.error_at(spec.root["base_axes"], "base_axes",
                                      "the three revolute axes are parallel: x and y of the platform would "
                                      "not be determined");
        }
        if (collinear(*base)) {
          return spec.reader.error_at(spec.root["base_joints"], "base_joints",
                                      "the three joints are collinear");
        }
        if (collinear(*platform)) {
          return spec.reader.error_at(spec.root["platform_joints"], "platform_joints",
                                      "the three joints are collinear");
        }

        PoseVector home = PoseVector::Zero();
        if (spec.home) {
          home = *spec.home;
        } else {
          home[2] = default_home_height_mm(*base, platform_tool, spec.limits);
        }
        auto tripod = Tripod::create(geometry, spec.convention, home);
        if (!tripod) {
          const YAML::Node where = spec.root["home"] ? spec.root["home"] : spec.root["platform_joints"];
          return spec.reader.error_at(where, "home", tripod.error().message);
        }
        return std::unique_ptr<Mechanism>(std::make_unique<Tripod>(std::move(tripod.value())));
      }};
}

}  // namespace pkm
