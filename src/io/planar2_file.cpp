// Machine-file entry of the planar 2-DOF mechanism: `base_joints` (A_1, A_2 as 2 numbers each, mm); `home` is
// the output joint B (x, y mm). There is no platform, so `tool` is rejected rather than silently ignored.
#include <cmath>

#include "io/mechanism_files.hpp"
#include "machine/planar2.hpp"

namespace pkm {
namespace {

/// Below this |A_1A_2| the base line, and with it the assembly-mode side, is undefined (mm).
constexpr double kMinBaseDistance_mm = 1e-6;
/// Below this sin(angle between the struts) the home pose counts as singular (B on line A_1A_2, eq. 78); a
/// home there would leave the assembly mode of every FK from it undefined.
constexpr double kMinHomeSine = 1e-6;

/// B on the +normal side (left of A_1 → A_2) of the midpoint of A_1A_2, with both struts at mid-range length
/// when limits allow it, else at |A_1A_2| (equilateral: the struts meet at 60°, far from the singularity).
Eigen::Vector2d default_home_mm(const Planar2Geometry& geometry, const ActuatorLimits& limits) {
  const Eigen::Vector2d a1 = geometry.base_joints_mm[0], a2 = geometry.base_joints_mm[1];
  const double d = (a2 - a1).norm();
  double length_mm = d;
  if (limits.min && limits.max) {
    const double mid_mm = 0.5 * (*limits.min + *limits.max);
    if (mid_mm > 0.55 * d) length_mm = mid_mm;  // 0.55: keep the struts clearly apart from the flat triangle
  }
  const Eigen::Vector2d along = (a2 - a1) / d;
  const Eigen::Vector2d normal(-along.y(), along.x());
  return 0.5 * (a1 + a2) + std::sqrt(length_mm * length_mm - 0.25 * d * d) * normal;
}

}  // namespace

MechanismFileEntry planar2_file_entry() {
  return {MechanismType::planar2,
          {"base_joints"},
          2,
          [](const MechanismSpec& spec) -> Result<std::unique_ptr<Mechanism>> {
            if (spec.root["tool"]) {
              return spec.reader.error_at(
                  spec.root["tool"], "tool",
                  "planar2 has no platform: the pose is the joint B where the struts meet; "
                  "remove this key");
            }
            auto base = spec.reader.points(spec.root, "base_joints", 2, 2);
            if (!base) return base.error();
            Planar2Geometry geometry;
            for (int j = 0; j < 2; ++j) geometry.base_joints_mm[j] = (*base)[j].head<2>();
            if ((geometry.base_joints_mm[1] - geometry.base_joints_mm[0]).norm() < kMinBaseDistance_mm) {
              return spec.reader.error_at(spec.root["base_joints"], "base_joints",
                                          "A1 and A2 coincide: the two struts need distinct base joints");
            }
            const Eigen::Vector2d home_mm = spec.home ? Eigen::Vector2d((*spec.home)[0], (*spec.home)[1])
                                                      : default_home_mm(geometry, spec.limits);
            auto planar2 = std::make_unique<Planar2>(geometry, home_mm);
            for (const auto& a : geometry.base_joints_mm) {
              if ((home_mm - a).norm() < kMinBaseDistance_mm) {
                return spec.reader.error_at(spec.root["home"], "home",
                                            "B is on a base joint at its home pose");
              }
            }
            if (!(std::abs(planar2->jacobian_determinant(home_mm)) >= kMinHomeSine)) {
              const YAML::Node where = spec.root["home"] ? spec.root["home"] : spec.root["base_joints"];
              return spec.reader.error_at(where, "home",
                                          "planar2 is singular at its home pose: B is on line A1A2 (D = 0); "
                                          "put B on the side the machine works on");
            }
            return std::unique_ptr<Mechanism>(std::move(planar2));
          }};
}

}  // namespace pkm
