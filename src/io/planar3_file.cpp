// Machine-file entry of the planar 3-RPR platform: `base_joints` (A_j, 3 points of 2 numbers, base frame, mm)
// and `platform_joints` (B'_j, 3 points of 2 numbers, platform frame, mm); the optional `tool: [x, y]`
// (platform frame) moves the pose origin to the tool point. `home` is x, y (mm) and phi (deg).
#include <Eigen/Geometry>
#include <cmath>

#include "core/units.hpp"
#include "io/mechanism_files.hpp"
#include "machine/planar3.hpp"

namespace pkm {
namespace {

/// Below this |normalized det J| (dimensionless, see Planar3::normalized_determinant) a home pose is
/// singular: the assembly mode of every FK from it would be undefined.
constexpr double kMinHomeDeterminant = 1e-6;
/// A default home should be clearly away from singularities, not just off them (dimensionless, max ≈ 2.8).
constexpr double kComfortableDeterminant = 0.05;

/// The platform-joint centroid over the base-joint centroid, at the first angle of 0, ±15°, ±30°, … ±90° that
/// is comfortably non-singular (with base and platform triangles similar, φ = 0 is singular everywhere: ch3
/// §4).
Eigen::Vector3d default_home(const Planar3Geometry& geometry) {
  Eigen::Vector2d base_centroid_mm = Eigen::Vector2d::Zero(), platform_centroid_mm = Eigen::Vector2d::Zero();
  for (int j = 0; j < 3; ++j) {
    base_centroid_mm += geometry.base_joints_mm[j] / 3.0;
    platform_centroid_mm += geometry.platform_joints_mm[j] / 3.0;
  }
  const Planar3 probe(geometry, Eigen::Vector3d::Zero());
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  double best_det = -1.0;
  for (double angle_deg : {0.0, 15.0, -15.0, 30.0, -30.0, 45.0, -45.0, 60.0, -60.0, 90.0, -90.0}) {
    const double phi = rad_from_deg(angle_deg);
    const Eigen::Vector2d arm = Eigen::Rotation2Dd(phi) * platform_centroid_mm;
    const Eigen::Vector3d candidate(base_centroid_mm.x() - arm.x(), base_centroid_mm.y() - arm.y(), phi);
    const double det = std::abs(probe.normalized_determinant(candidate));
    if (det >= kComfortableDeterminant) return candidate;
    if (det > best_det) {
      best_det = det;
      best = candidate;
    }
  }
  return best;
}

}  // namespace

MechanismFileEntry planar3_file_entry() {
  return {MechanismType::planar3,
          {"base_joints", "platform_joints"},
          3,
          [](const MechanismSpec& spec) -> Result<std::unique_ptr<Mechanism>> {
            auto base = spec.reader.points(spec.root, "base_joints", 3, 2);
            if (!base) return base.error();
            auto platform = spec.reader.points(spec.root, "platform_joints", 3, 2);
            if (!platform) return platform.error();
            Planar3Geometry geometry;
            for (int j = 0; j < 3; ++j) {
              geometry.base_joints_mm[j] = (*base)[j].head<2>();
              geometry.platform_joints_mm[j] = ((*platform)[j] - spec.tool_mm).head<2>();
            }
            const Eigen::Vector3d home =
                spec.home ? Eigen::Vector3d((*spec.home)[0], (*spec.home)[1], (*spec.home)[5])
                          : default_home(geometry);
            auto planar3 = std::make_unique<Planar3>(geometry, home);
            if (!(std::abs(planar3->normalized_determinant(home)) >= kMinHomeDeterminant)) {
              const YAML::Node where = spec.root["home"] ? spec.root["home"] : spec.root["platform_joints"];
              return spec.reader.error_at(
                  where, "home",
                  "planar3 is singular at its home pose (det J = 0: the three strut lines "
                  "meet in one point or are parallel); choose another home");
            }
            return std::unique_ptr<Mechanism>(std::move(planar3));
          }};
}

}  // namespace pkm
