#include "calibration/synthetic_measurements.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace pkm::calibration {

namespace {
// The true machine's pose to round-off: noise-free data must identify the parameters to 1e-8 mm.
const FkOptions kSimulationFk{1e-12, 60, 1e-13, true};
}  // namespace

std::vector<FixtureTarget> triangular_plate(double radius_mm) {
  std::vector<FixtureTarget> plate;
  for (int k = 0; k < 3; ++k) {
    const double angle = std::numbers::pi / 2.0 + 2.0 * std::numbers::pi * k / 3.0;
    plate.push_back({fmt::format("S{}", k + 1),
                     Eigen::Vector3d(radius_mm * std::cos(angle), radius_mm * std::sin(angle), 0.0)});
  }
  return plate;
}

MeasurementSetup target_setup(double sigma_mm, std::vector<FixtureTarget> fixture) {
  MeasurementSetup setup;
  setup.kind = MeasurementKind::targets;
  setup.fixture = std::move(fixture);
  setup.sigma_mm = sigma_mm;
  return setup;
}

MeasurementSetup ballbar_setup(const Eigen::Vector3d& centre_mm, double sigma_mm) {
  MeasurementSetup setup;
  setup.kind = MeasurementKind::ballbar;
  setup.ballbar_centre_mm = centre_mm;
  setup.sigma_mm = sigma_mm;
  return setup;
}

Result<MeasurementSet> simulate_measurements(const Mechanism& nominal, const Mechanism& truth,
                                             const std::vector<Pose>& plan, const MeasurementSetup& setup,
                                             std::mt19937_64* noise) {
  MeasurementSet set;
  set.source = "simulated";
  set.kind = setup.kind;
  set.fixture = setup.fixture;
  set.ballbar_centre_mm = setup.ballbar_centre_mm;
  std::normal_distribution<double> gauss(0.0, setup.sigma_mm);
  auto noisy = [&](double value) { return noise ? value + gauss(*noise) : value; };
  for (std::size_t i = 0; i < plan.size(); ++i) {
    auto readings = nominal.inverse(plan[i]);
    if (!readings) {
      return make_error(readings.error().code,
                        fmt::format("planned pose {}: {}", i + 1, readings.error().message));
    }
    auto reached = truth.forward(*readings, plan[i], kSimulationFk);
    if (!reached) {
      return make_error(reached.error().code,
                        fmt::format("planned pose {}: the true machine has no forward solution ({})", i + 1,
                                    reached.error().message));
    }
    MeasuredPose measured;
    measured.id = fmt::format("P{}", i + 1);
    measured.readings = *readings;
    if (setup.kind == MeasurementKind::targets) {
      for (std::size_t k = 0; k < setup.fixture.size(); ++k) {
        const Eigen::Vector3d exact = reached->pose.to_base(setup.fixture[k].position_mm);
        TargetObservation o;
        o.target = static_cast<int>(k);
        o.position_mm = Eigen::Vector3d(noisy(exact.x()), noisy(exact.y()), noisy(exact.z()));
        o.sigma_mm = setup.sigma_mm;
        measured.targets.push_back(o);
      }
    } else {
      DistanceObservation d;
      d.distance_mm = noisy((reached->pose.position_mm - setup.ballbar_centre_mm).norm());
      d.sigma_mm = setup.sigma_mm;
      measured.distances.push_back(d);
    }
    set.poses.push_back(std::move(measured));
  }
  return set;
}

}  // namespace pkm::calibration
