// The elastic machine's energy (the model of Smirnov 2019, §4.5), on the ch5 hexapod, the planar biped and
// five random hexapods with random inertial and elastic parameters, the drives held:
//  - without friction, T + Π + V_g stays what it was to 1e-8 of the vibration's energy over ten periods of
//    the slowest mode (the printed (141) flips the spring's sign: that would not conserve anything). T and
//    V_g come from body_motion's own functions, not from the right-hand side's matrices, so the test also
//    checks rigid_terms against them;
//  - with viscous, quadratic or Coulomb friction it never grows (to the integrator's tolerance) and the
//    vibration loses a good part of its energy within twenty periods.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dynamics/dynamics_test_support.hpp"
#include "dynamics/elastic_equilibrium.hpp"
#include "dynamics/elastic_simulation.hpp"
#include "dynamics/natural_frequencies.hpp"

namespace pkm {
namespace {

using dynamics::CoordinateVector;

/// The energies of a free vibration from the static equilibrium at home, started with `rates`, sampled 20
/// times per period of the slowest mode for `periods` periods; [0] is the start.
struct FreeVibration {
  std::vector<dynamics::ElasticEnergy> energy;
  double rest_J = 0.0;  ///< Π + V_g at rest in the equilibrium: the energy the vibration decays to
  long steps = 0;
};

FreeVibration energy_free_vibration(const dynamics::ElasticModel& model, const CoordinateVector& rates,
                                    double periods, const dynamics::ElasticIntegration& integration) {
  FreeVibration out;
  const Mechanism& mech = *model.mechanism;
  auto modes = dynamics::natural_modes(model, mech.home());
  EXPECT_TRUE(modes.ok()) << modes.error().message;
  if (!modes) return out;
  const dynamics::StaticEquilibrium& eq = modes->equilibrium;
  const dynamics::HeldDrives drives(eq.drive_position_mm);
  auto at_rest = dynamics::elastic_energy(model, eq.pose, CoordinateVector::Zero(model.coordinates),
                                          eq.drive_position_mm);
  out.rest_J = at_rest->total_J();
  dynamics::ElasticSimulator simulator(model, integration);
  EXPECT_TRUE(simulator.start(0.0, eq.pose, rates).ok());
  out.energy.push_back(*dynamics::elastic_energy(model, eq.pose, rates, eq.drive_position_mm));
  const double dt = 1.0 / modes->frequency_Hz[0] / 20.0;
  for (int k = 1; k <= static_cast<int>(20 * periods); ++k) {
    const Status advanced = simulator.advance_to(k * dt, drives);
    EXPECT_TRUE(advanced.ok()) << advanced.error().message;
    if (!advanced) break;
    out.energy.push_back(
        *dynamics::elastic_energy(model, simulator.pose(), simulator.rates(), eq.drive_position_mm));
  }
  out.steps = simulator.counters().accepted_steps;
  return out;
}

/// A twist of 25–50 mm/s and 0.05–0.1 rad/s in a random direction (planar: the basis' components): a
/// vibration of some 10 µm.
CoordinateVector energy_initial_rates(std::mt19937_64& rng, const dynamics::ElasticModel& model) {
  CoordinateVector rates(model.coordinates);
  for (int k = 0; k < model.coordinates; ++k) {
    const bool angular = model.basis.col(k).tail<3>().squaredNorm() > 0.0;
    rates[k] =
        (angular ? 0.05 : 25.0) * test::uniform(rng, 1.0, 2.0) * (test::uniform(rng, 0, 1) < 0.5 ? -1 : 1);
  }
  return rates;
}

TEST(ElasticEnergy, FreeUndampedVibrationConservesTheTotalEnergy) {
  std::vector<test::ElasticCase> cases = test::elastic_cases(StrutDamping::none);
  std::mt19937_64 rng(31);
  dynamics::ElasticIntegration tight;
  tight.abs_tolerance_mm = 3e-14;
  tight.rel_tolerance = 1e-15;
  double worst = 0.0;
  for (const test::ElasticCase& c : cases) {
    SCOPED_TRACE(c.label);
    auto model = dynamics::make_elastic_model(*c.machine.mechanism, c.parameters);
    ASSERT_TRUE(model.ok()) << model.error().message;
    const FreeVibration run = energy_free_vibration(*model, energy_initial_rates(rng, *model), 10, tight);
    ASSERT_GT(run.energy.size(), 200u);
    const double start_J = run.energy[0].total_J();
    const double vibration_J = start_J - run.rest_J;
    EXPECT_NEAR(vibration_J, run.energy[0].kinetic_J, 1e-9 * vibration_J);  // it starts at the equilibrium
    double drift = 0.0, elastic_peak_J = 0.0;
    for (const dynamics::ElasticEnergy& e : run.energy) {
      drift = std::max(drift, std::abs(e.total_J() - start_J) / vibration_J);
      elastic_peak_J = std::max(elastic_peak_J, e.elastic_J);
    }
    // The energy does move between kinetic and elastic (the struts do work): not a trivially still run.
    EXPECT_GT(elastic_peak_J - run.energy[0].elastic_J, 0.1 * vibration_J);
    EXPECT_LE(drift, 1e-8) << "relative drift of T + Π + V_g over 10 periods (" << run.steps << " steps)";
    worst = std::max(worst, drift);
  }
  RecordProperty("worst_relative_energy_drift", fmt::format("{:.3g}", worst));
}

TEST(ElasticEnergy, StrutFrictionNeverAddsEnergy) {
  dynamics::ElasticIntegration integration;
  integration.abs_tolerance_mm = 1e-11;
  integration.rel_tolerance = 1e-13;
  for (StrutDamping damping : {StrutDamping::viscous, StrutDamping::quadratic, StrutDamping::coulomb}) {
    std::vector<test::ElasticCase> cases = test::elastic_cases(damping, -1, 41);
    std::mt19937_64 rng(43);
    for (const test::ElasticCase& c : cases) {
      SCOPED_TRACE(fmt::format("{}, friction model {}", c.label, static_cast<int>(damping)));
      auto model = dynamics::make_elastic_model(*c.machine.mechanism, c.parameters);
      ASSERT_TRUE(model.ok()) << model.error().message;
      // Twice the conservation test's speeds: the quadratic and Coulomb forces need a real vibration.
      const FreeVibration run =
          energy_free_vibration(*model, 2.0 * energy_initial_rates(rng, *model), 20, integration);
      ASSERT_GT(run.energy.size(), 400u);
      const double vibration_J = run.energy[0].total_J() - run.rest_J;
      for (std::size_t k = 1; k < run.energy.size(); ++k) {
        ASSERT_LE(run.energy[k].total_J(), run.energy[k - 1].total_J() + 1e-9 * vibration_J)
            << "sample " << k << " of " << run.energy.size();
      }
      EXPECT_LT(run.energy.back().total_J() - run.rest_J, 0.9 * vibration_J);
    }
  }
}

}  // namespace
}  // namespace pkm
