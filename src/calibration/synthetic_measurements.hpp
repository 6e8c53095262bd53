#pragma once
// Measurements made by simulation: what a tracker, a CMM or a ballbar would record on a machine
// whose true geometry differs from its drawing. The controller commands each planned pose P with the NOMINAL
// model (readings = IK_nominal(P)); the real machine then stands at FK_true(readings); the instrument sees
// that pose's targets (or the ballbar's length) with Gaussian noise. Plan design (plan_design.hpp) uses the
// same measurements without noise and with truth = nominal to predict what a plan can identify.
#include <Eigen/Core>
#include <random>
#include <vector>

#include "core/pose.hpp"
#include "core/result.hpp"
#include "io/measurements.hpp"
#include "machine/mechanism.hpp"

namespace pkm::calibration {

/// What is measured at every pose of a plan.
struct MeasurementSetup {
  MeasurementKind kind = MeasurementKind::targets;
  std::vector<FixtureTarget> fixture;                           ///< kind targets
  Eigen::Vector3d ballbar_centre_mm = Eigen::Vector3d::Zero();  ///< kind ballbar
  double sigma_mm = 0.01;  ///< standard deviation of each measured coordinate or length
};

/// The dissertation's fixture (Smirnov 2019, Fig. 186): a thin equilateral triangle whose vertices S1..S3
/// lie on a circle of `radius_mm` about the tool point in the tool frame's xy plane (at 90°, 210°, 330°).
std::vector<FixtureTarget> triangular_plate(double radius_mm = 100.0);

/// A tracker or CMM measuring the targets of `fixture` (default: the triangular plate) with `sigma_mm`.
MeasurementSetup target_setup(double sigma_mm, std::vector<FixtureTarget> fixture = triangular_plate());
/// A ballbar from the tool point to a ball at `centre_mm` (base frame), length measured with `sigma_mm`.
MeasurementSetup ballbar_setup(const Eigen::Vector3d& centre_mm, double sigma_mm);

/// The measurements of `plan` on `truth` commanded through `nominal` (both the same kind of mechanism; the
/// nominal's IK gives the readings). Noise N(0, σ²) on every measured coordinate from `noise`, none when
/// null. Fails, naming the pose, where the nominal cannot reach a planned pose or the true machine has no
/// forward solution for its readings.
Result<MeasurementSet> simulate_measurements(const Mechanism& nominal, const Mechanism& truth,
                                             const std::vector<Pose>& plan, const MeasurementSetup& setup,
                                             std::mt19937_64* noise);

}  // namespace pkm::calibration
