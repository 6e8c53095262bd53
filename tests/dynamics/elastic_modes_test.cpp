// Natural frequencies of the elastic machine (beyond Smirnov 2019, §4.5), on the ch5 hexapod, the planar
// biped and five random hexapods with random inertial and elastic parameters:
//  - the static equilibrium carries gravity: the struts' forces are the rigid model's drive forces at rest
//    with the opposite sign (a stretched strut pulls its platform joint towards the base), and the sag
//    falls as 1/c;
//  - without gravity, scaling every stiffness by k scales every frequency by √k (to 1e-10);
//  - the lowest linearised frequency is the one the nonlinear simulation vibrates at: the peak of the
//    discrete Fourier transform of a free response along that mode (≥ 200 periods, Hann window, parabolic
//    interpolation of the log magnitude) is within 0.5 % of it;
//  - the map over poses gives each pose's lowest frequency, and NaN where there is none (a singular pose).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "dynamics/dynamics_test_support.hpp"
#include "dynamics/elastic_simulation.hpp"
#include "dynamics/natural_frequencies.hpp"
#include "dynamics/rigid_dynamics.hpp"

namespace pkm {
namespace {

using dynamics::CoordinateVector;

TEST(ElasticModes, TheEquilibriumStrutForcesAreTheRigidDriveForcesReversedAndTheSagFallsAsOneOverC) {
  std::vector<test::ElasticCase> cases = test::elastic_cases(StrutDamping::none);
  for (test::ElasticCase& c : cases) {
    SCOPED_TRACE(c.label);
    const Mechanism& mech = *c.machine.mechanism;
    auto model = dynamics::make_elastic_model(mech, c.parameters);
    ASSERT_TRUE(model.ok()) << model.error().message;
    auto modes = dynamics::natural_modes(*model, mech.home());
    ASSERT_TRUE(modes.ok()) << modes.error().message;
    // The rigid model's drives at the sagged pose (where the tension balances gravity exactly).
    dynamics::PlatformMotion at_rest;
    at_rest.pose = modes->equilibrium.pose;
    auto drives = dynamics::inverse_dynamics(mech, c.parameters, at_rest);
    ASSERT_TRUE(drives.ok());
    const ActuatorVector& tension = modes->equilibrium.strut_force_N;
    EXPECT_LE((tension + drives->total).cwiseAbs().maxCoeff(), 1e-9 * drives->total.cwiseAbs().maxCoeff())
        << "strut tension " << tension.transpose() << "\nrigid drives  " << drives->total.transpose();
    // Rounding: the struts' forces of ~10³ N balance each other's moments of ~10⁶ N·mm down to the load.
    EXPECT_LE(modes->equilibrium.residual, 1e-8);
    const double sag_mm = (modes->equilibrium.pose.position_mm - mech.home().position_mm).norm();
    EXPECT_GT(sag_mm, 0.0);
    for (int j = 0; j < c.parameters.strut_count; ++j) c.parameters.struts[j].stiffness_N_mm *= 100.0;
    auto stiffer = dynamics::natural_modes(*model, mech.home());
    ASSERT_TRUE(stiffer.ok());
    const double stiffer_sag_mm = (stiffer->equilibrium.pose.position_mm - mech.home().position_mm).norm();
    // To first order in the sag: the shipped machines sag by microns (1e-4); some random ones, up to 20 times
    // softer and loaded off-centre, by up to 0.3 mm, where the struts' turning shows at the per cent level.
    const bool shipped = c.label.find("random") == std::string::npos;
    EXPECT_NEAR(stiffer_sag_mm * 100.0, sag_mm, (shipped ? 1e-4 : 2e-2) * sag_mm);
  }
}

TEST(ElasticModes, WithoutGravityFrequenciesScaleWithTheSquareRootOfTheStiffness) {
  std::vector<test::ElasticCase> cases = test::elastic_cases(StrutDamping::none);
  double worst = 0.0;
  for (test::ElasticCase& c : cases) {
    SCOPED_TRACE(c.label);
    c.parameters.gravity_mm_s2.setZero();
    auto model = dynamics::make_elastic_model(*c.machine.mechanism, c.parameters);
    ASSERT_TRUE(model.ok()) << model.error().message;
    const Pose pose = c.machine.mechanism->home();
    auto modes = dynamics::natural_modes(*model, pose);
    ASSERT_TRUE(modes.ok()) << modes.error().message;
    EXPECT_EQ(modes->geometric_share, 0.0);  // no preload without gravity
    for (double k : {7.3, 1e3}) {
      SCOPED_TRACE(fmt::format("k = {}", k));
      DynamicsParameters scaled = c.parameters;
      for (int j = 0; j < scaled.strut_count; ++j) scaled.struts[j].stiffness_N_mm *= k;
      auto scaled_model = dynamics::make_elastic_model(*c.machine.mechanism, scaled);
      ASSERT_TRUE(scaled_model.ok());
      auto scaled_modes = dynamics::natural_modes(*scaled_model, pose);
      ASSERT_TRUE(scaled_modes.ok());
      for (int i = 0; i < modes->count; ++i) {
        const double ratio = scaled_modes->frequency_Hz[i] / modes->frequency_Hz[i];
        EXPECT_NEAR(ratio, std::sqrt(k), 1e-10 * std::sqrt(k)) << "mode " << i;
        worst = std::max(worst, std::abs(ratio / std::sqrt(k) - 1.0));
      }
    }
  }
  RecordProperty("worst_relative_sqrt_k_deviation", fmt::format("{:.3g}", worst));
}

/// |X(k)| of the Hann-windowed samples at the (fractional) bin k: X = Σ w_n x_n e^{−2πi k n / N}.
double modes_dft_magnitude(const std::vector<double>& x, double bin) {
  const double n_total = static_cast<double>(x.size());
  std::complex<double> sum = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    const double hann = 0.5 - 0.5 * std::cos(2 * kPi * n / n_total);
    sum += hann * x[n] * std::polar(1.0, -2 * kPi * bin * n / n_total);
  }
  return std::abs(sum);
}

/// The peak frequency of `x` sampled every `dt`: the largest of the bins around `expected_Hz`, refined by a
/// parabola through the log magnitudes of it and its neighbours (exact for a Gaussian peak, and the Hann
/// window's main lobe is close to one).
double modes_peak_frequency(const std::vector<double>& x, double dt, double expected_Hz) {
  const double record_s = x.size() * dt;
  const int centre = static_cast<int>(std::lround(expected_Hz * record_s));
  int best = centre;
  for (int k = centre - 3; k <= centre + 3; ++k)
    if (modes_dft_magnitude(x, k) > modes_dft_magnitude(x, best)) best = k;
  const double left = std::log(modes_dft_magnitude(x, best - 1));
  const double middle = std::log(modes_dft_magnitude(x, best));
  const double right = std::log(modes_dft_magnitude(x, best + 1));
  const double offset = 0.5 * (left - right) / (left - 2 * middle + right);
  return (best + offset) / record_s;
}

TEST(ElasticModes, TheLowestFrequencyIsTheOneTheSimulationVibratesAt) {
  std::vector<test::ElasticCase> cases = test::elastic_cases(StrutDamping::none);
  dynamics::ElasticIntegration integration;
  integration.abs_tolerance_mm = 1e-11;
  integration.rel_tolerance = 1e-13;
  double worst = 0.0;
  for (const test::ElasticCase& c : cases) {
    SCOPED_TRACE(c.label);
    auto model = dynamics::make_elastic_model(*c.machine.mechanism, c.parameters);
    ASSERT_TRUE(model.ok()) << model.error().message;
    auto modes = dynamics::natural_modes(*model, c.machine.mechanism->home());
    ASSERT_TRUE(modes.ok()) << modes.error().message;
    const double f_Hz = modes->frequency_Hz[0];
    const CoordinateVector shape = modes->shape.col(0);
    // 1 µm along the mode from the equilibrium, at rest: the response is that mode's vibration (and it is
    // what is measured: the displacement's mass-weighted projection on the mode).
    const dynamics::StaticEquilibrium& eq = modes->equilibrium;
    dynamics::ElasticSimulator simulator(*model, integration);
    ASSERT_TRUE(simulator
                    .start(0.0, dynamics::displaced_pose(*model, eq.pose, 1e-3 * shape),
                           CoordinateVector::Zero(model->coordinates))
                    .ok());
    const dynamics::HeldDrives drives(eq.drive_position_mm);
    // 16 samples per expected period, 219.8 periods: the expected peak falls between two bins (at 219.8),
    // so the interpolation has to find it.
    const int per_period = 16, samples = 3517;
    const double dt = 1.0 / f_Hz / per_period;
    std::vector<double> response;
    for (int k = 1; k <= samples; ++k) {
      ASSERT_TRUE(simulator.advance_to(k * dt, drives).ok());
      const CoordinateVector d = dynamics::pose_displacement(*model, eq.pose, simulator.pose());
      response.push_back(shape.dot(modes->mass * d));
    }
    const double measured_Hz = modes_peak_frequency(response, dt, f_Hz);
    const double difference = std::abs(measured_Hz - f_Hz) / f_Hz;
    EXPECT_LE(difference, 0.005) << "linearised " << f_Hz << " Hz, simulated " << measured_Hz << " Hz";
    worst = std::max(worst, difference);
  }
  RecordProperty("worst_relative_frequency_difference", fmt::format("{:.3g}", worst));
}

TEST(ElasticModes, TheMapGivesEachPosesLowestFrequencyAndNanWhereThereIsNone) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto model = dynamics::make_elastic_model(machine);
  ASSERT_TRUE(model.ok()) << model.error().message;
  std::vector<Pose> poses;
  for (double x : {-40.0, 0.0, 40.0}) {
    for (double z : {650.0, 750.0}) poses.push_back(test::abc_pose(x, 0, z, 0, 0, 0));
  }
  // The platform's joints in the base joints' plane (the tool 150 mm above them): the struts hold nothing up.
  poses.push_back(test::abc_pose(0, 0, 150, 0, 0, 0));
  const std::vector<double> map = dynamics::lowest_frequency_map(*model, poses);
  ASSERT_EQ(map.size(), poses.size());
  for (std::size_t i = 0; i + 1 < poses.size(); ++i) {
    auto modes = dynamics::natural_modes(*model, poses[i]);
    ASSERT_TRUE(modes.ok());
    EXPECT_EQ(map[i], modes->frequency_Hz[0]);
    EXPECT_GT(map[i], 50.0);
    EXPECT_LT(map[i], 500.0);
  }
  EXPECT_TRUE(std::isnan(map.back()));
  // The struts' angles change with the height, and with them the sideways stiffness of the lowest mode.
  EXPECT_GT(std::abs(map[0] - map[1]), 1e-3 * map[0]);
}

}  // namespace
}  // namespace pkm
