#include "machine/kinematics_timing.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "core/units.hpp"

namespace pkm {
namespace {

// splitmix64: a small, seedable generator so timings are repeatable.
double uniform_pm1(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return 2.0 * (static_cast<double>(z >> 11) * 0x1.0p-53) - 1.0;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Pose random_pose_near(const Mechanism& mechanism, const Pose& centre, double range_mm, double range_rad,
                      std::uint64_t& state) {
  PoseVector c = vector_from_pose(mechanism.convention(), centre);
  const AxisMask mask = mechanism.controlled_axes();
  for (int axis = 0; axis < 6; ++axis) {
    if (mask.controlled[axis]) c[axis] += uniform_pm1(state) * (axis < 3 ? range_mm : range_rad);
  }
  auto completed = mechanism.complete_pose(pose_from_vector(mechanism.convention(), c));
  return completed ? *completed : centre;
}

KinematicsTiming time_kinematics(const Mechanism& mechanism, const KinematicsTimingOptions& o) {
  KinematicsTiming t;
  std::uint64_t state = o.seed;
  const Pose home = mechanism.home();

  // IK from the six pose coordinates (angles in the mechanism's convention), as a controller hands them over
  // (LinuxCNC's kinematicsInverse gets an EmcPose): the angles → matrix conversion is in the time.
  std::vector<PoseVector> poses;
  poses.reserve(static_cast<std::size_t>(o.ik_poses));
  for (int i = 0; i < o.ik_poses; ++i) {
    poses.push_back(vector_from_pose(
        mechanism.convention(),
        random_pose_near(mechanism, home, o.ik_range_mm, rad_from_deg(o.ik_range_deg), state)));
  }
  double checksum = 0.0;
  auto start = std::chrono::steady_clock::now();
  // The servo-loop forms of the interface: hot IK into caller storage, warm FK with the mechanism's own
  // workspace (what interpolation, a LinuxCNC module and the bindings call).
  std::array<double, kMaxActuators> values{};
  for (const PoseVector& p : poses) {
    if (mechanism.actuator_values_at(mechanism.convention(), p, values.data())) checksum += values[0];
  }
  t.ik_ns_per_pose = seconds_since(start) * 1e9 / o.ik_poses;

  // A smooth path: a circle of radius 40 mm in the controlled translations with slowly turning angles.
  std::vector<Pose> path;
  std::vector<ActuatorVector> path_q;
  const PoseVector c0 = vector_from_pose(mechanism.convention(), home);
  const AxisMask mask = mechanism.controlled_axes();
  const double step_rad = 0.1 / 40.0;  // 0.1 mm of arc per step
  for (int i = 0; i < o.path_poses; ++i) {
    PoseVector c = c0;
    const double s = i * step_rad;
    if (mask.controlled[0]) c[0] += 40.0 * std::sin(s);
    if (mask.controlled[1]) c[1] += 40.0 * (1.0 - std::cos(s));
    if (mask.controlled[2]) c[2] += 10.0 * std::sin(0.3 * s);
    for (int axis = 3; axis < 6; ++axis) {
      // 0.01° per step, folded back and forth within ±5°
      if (mask.controlled[axis])
        c[axis] += rad_from_deg(5.0) * std::sin(i * rad_from_deg(0.01) / rad_from_deg(5.0));
    }
    auto pose = mechanism.complete_pose(pose_from_vector(mechanism.convention(), c));
    if (!pose) break;
    auto q = mechanism.inverse(*pose);
    if (!q) break;
    path.push_back(*pose);
    path_q.push_back(*q);
  }
  if (path.size() > 1) {
    long iterations = 0, converged = 0;
    Pose previous = path.front();
    const std::unique_ptr<FkWorkspace> workspace = mechanism.make_fk_workspace();
    const FkOptions fk_options;
    start = std::chrono::steady_clock::now();
    for (std::size_t i = 1; i < path.size(); ++i) {
      auto fk = mechanism.forward_warm(path_q[i], previous, fk_options, *workspace);
      if (fk) {
        iterations += fk->iterations;
        previous = fk->pose;
        converged += (fk->pose.position_mm - path[i].position_mm).norm() < 1e-6 ? 1 : 0;
      } else {
        previous = path[i];
      }
    }
    const double n = static_cast<double>(path.size() - 1);
    t.fk_us_per_solve_warm = seconds_since(start) * 1e6 / n;
    t.fk_iterations_warm = static_cast<double>(iterations) / n;
    t.fk_converged_warm = static_cast<double>(converged) / n;
  }

  std::vector<Pose> cold;
  std::vector<ActuatorVector> cold_q;
  for (int i = 0; i < o.cold_poses; ++i) {
    const Pose p = random_pose_near(mechanism, home, o.cold_range_mm, rad_from_deg(o.cold_range_deg), state);
    auto q = mechanism.inverse(p);
    if (!q) continue;
    cold.push_back(p);
    cold_q.push_back(*q);
  }
  if (!cold.empty()) {
    long iterations = 0, converged = 0;
    start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < cold.size(); ++i) {
      auto fk = mechanism.forward(cold_q[i], home);
      if (fk) {
        iterations += fk->iterations;
        converged += (fk->pose.position_mm - cold[i].position_mm).norm() < 1e-6 ? 1 : 0;
      }
    }
    const double n = static_cast<double>(cold.size());
    t.fk_us_per_solve_cold = seconds_since(start) * 1e6 / n;
    t.fk_iterations_cold = static_cast<double>(iterations) / n;
    t.fk_converged_cold = static_cast<double>(converged) / n;
  }
  if (checksum == 12345.678) t.ik_ns_per_pose += 0;  // keep the IK loop observable
  return t;
}

}  // namespace pkm
