// A hexapod built from its geometry in code (no machine file), linked against the installed pkm::kinematics:
// inverse kinematics of a pose, then forward kinematics back through the Mechanism interface (the servo-loop
// form with the mechanism's own workspace). Exits non-zero when the round trip misses by more than 1e-9 mm.
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/pose.hpp"
#include "core/units.hpp"
#include "machine/hexapod.hpp"
#include "machine/mechanism.hpp"

int main() {
  using namespace pkm;

  // Base joints on a 400 mm circle every 60 degrees; platform joints merged in pairs (6-3) on a 200 mm
  // circle, given in the tool frame: the tool point is 150 mm above the platform-joint plane.
  HexapodGeometry geometry;
  for (int j = 0; j < 6; ++j) {
    const double base_angle = rad_from_deg(60.0 * j);
    geometry.base_joints_mm[j] =
        Eigen::Vector3d(400.0 * std::cos(base_angle), 400.0 * std::sin(base_angle), 0.0);
    const double platform_angle = rad_from_deg(30.0 + 120.0 * (j / 2));
    geometry.platform_joints_mm[j] =
        Eigen::Vector3d(200.0 * std::cos(platform_angle), 200.0 * std::sin(platform_angle), -150.0);
  }
  PoseVector home_coordinates;
  home_coordinates << 0.0, 0.0, 700.0, 0.0, 0.0, 0.0;
  const Pose home = pose_from_vector(AngleConvention::krylov, home_coordinates);
  const Hexapod hexapod(geometry, AngleConvention::krylov, home);
  const Mechanism& mechanism = hexapod;

  PoseVector target_coordinates;
  target_coordinates << 10.0, -20.0, 650.0, rad_from_deg(5.0), rad_from_deg(-3.0), rad_from_deg(2.0);
  const Pose target = pose_from_vector(AngleConvention::krylov, target_coordinates);

  const auto lengths = mechanism.inverse(target);
  if (!lengths.ok()) {
    std::fprintf(stderr, "inverse kinematics failed: %s\n", lengths.error().message.c_str());
    return 1;
  }
  std::printf("strut lengths (mm):");
  for (int j = 0; j < mechanism.actuator_count(); ++j) std::printf(" %.10f", (*lengths)[j]);
  std::printf("\n");

  std::unique_ptr<FkWorkspace> workspace = mechanism.make_fk_workspace();
  const auto solution = mechanism.forward_warm(*lengths, home, FkOptions{}, *workspace);
  if (!solution.ok()) {
    std::fprintf(stderr, "forward kinematics failed: %s\n", solution.error().message.c_str());
    return 1;
  }
  const PoseDistance error = pose_distance(solution->pose, target);
  std::printf("forward kinematics: %d iterations, round-trip error %.3g mm, %.3g rad\n", solution->iterations,
              error.position_mm, error.rotation_rad);
  if (!(error.position_mm <= 1e-9) || !(error.rotation_rad <= 1e-9)) {
    std::fprintf(stderr, "round trip error above 1e-9\n");
    return 1;
  }
  std::printf("ok\n");
  return 0;
}
