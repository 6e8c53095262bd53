// The process load in the elastic machine (src/dynamics/elastic_model.hpp, run_elastic.hpp): under a constant
// load with the drives held, the damped platform settles where the linearised stiffness says, δ = K⁻¹ w (K
// of natural_modes, the preload's geometric part included); and along a planned run a cutting load makes
// the dynamic tool error grow by about the compliance times the load.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/cli_support.hpp"
#include "core/rotation.hpp"
#include "dynamics/dynamics_test_support.hpp"
#include "dynamics/elastic_simulation.hpp"
#include "dynamics/natural_frequencies.hpp"

namespace pkm {
namespace {

using dynamics::CoordinateVector;

/// Drives held where they are, a constant load on the platform.
class HeldDrivesUnderLoad final : public dynamics::DriveMotion {
 public:
  HeldDrivesUnderLoad(const ActuatorVector& position_mm, const statics::Wrench& load)
      : position_mm_(position_mm), load_(load) {}
  void setpoint(double, dynamics::DriveSetpoint& out) const override {
    out.position_mm = position_mm_;
    out.rate_mm_s = ActuatorVector::Zero(position_mm_.size());
    out.load = load_;
  }

 private:
  ActuatorVector position_mm_;
  statics::Wrench load_;
};

TEST(ElasticLoad, UnderAConstantLoadThePlatformSettlesWhereTheStiffnessSays) {
  std::mt19937_64 rng(31);
  std::vector<test::ElasticCase> cases = test::elastic_cases(StrutDamping::viscous);
  for (test::ElasticCase& c : cases) {
    SCOPED_TRACE(c.label);
    // Heavy viscous friction (about a third of critical for the struts), so the step response dies out fast.
    for (int j = 0; j < c.parameters.strut_count; ++j) c.parameters.struts[j].damping_coefficient = 100.0;
    auto model = dynamics::make_elastic_model(*c.machine.mechanism, c.parameters);
    ASSERT_TRUE(model.ok()) << model.error().message;
    const Mechanism& mech = *c.machine.mechanism;
    auto modes = dynamics::natural_modes(*model, mech.home());
    ASSERT_TRUE(modes.ok()) << modes.error().message;
    const dynamics::StaticEquilibrium& rest = modes->equilibrium;
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    statics::Wrench load{Eigen::Vector3d(400 * unit(rng), 400 * unit(rng), 400 * unit(rng)),
                         Eigen::Vector3d(2e4 * unit(rng), 2e4 * unit(rng), 2e4 * unit(rng))};
    if (mech.is_planar())
      load = {Eigen::Vector3d(400 * unit(rng), 400 * unit(rng), 0), Eigen::Vector3d(0, 0, 0)};
    // Expected: K δ = Bᵀ w (kg·mm/s² per basis coordinate).
    dynamics::Twist wrench_kg;
    wrench_kg << load.force_N * 1e3, load.moment_Nmm * 1e3;
    const CoordinateVector generalised = model->basis.transpose() * wrench_kg;
    const CoordinateVector expected = modes->stiffness.llt().solve(generalised);
    ASSERT_GT(expected.head(2).norm(), 1e-4);  // a deflection of at least 0.1 µm to see

    const HeldDrivesUnderLoad drives(rest.drive_position_mm, load);
    dynamics::ElasticSimulator simulator(*model);
    ASSERT_TRUE(simulator.start(0.0, rest.pose, CoordinateVector::Zero(model->coordinates)).ok());
    ASSERT_TRUE(simulator.advance_to(0.5, drives).ok());
    const Pose settled = simulator.pose();
    dynamics::Twist displacement;
    displacement << settled.position_mm - rest.pose.position_mm,
        rotation_vector_from_rotation(settled.rotation * rest.pose.rotation.transpose());
    const CoordinateVector actual = model->basis.transpose() * displacement;
    // Linearised against the exact machine: the deflections are µm, so they agree to far better than 1 %.
    EXPECT_LE((actual - expected).norm(), 1e-2 * expected.norm())
        << "simulated " << actual.transpose() << "\nK⁻¹ w     " << expected.transpose();
    // At rest again: what is left of the step response moves it by less than 1 % of the deflection.
    const double omega_lowest = 2 * kPi * modes->frequency_Hz[0];
    EXPECT_LT(simulator.rates().norm() / omega_lowest, 1e-2 * expected.norm());
  }
}

double elastic_load_max_error_mm(const std::string& load) {
  const std::string out = (std::filesystem::temp_directory_path() / "pkm_elastic_load").string();
  std::filesystem::remove_all(out);
  // A 40 mm feed (about 1 s of motion): the sanitizer run of CI pays for every elastic tick.
  const std::string program = test::write_temp_file(
      "elastic_load_line.ngc", "G21 G90 G17 G94\nG0 X-20 Y0 Z0\nG1 X20 Y10 F3000\nG1 X20 Y30\nM2\n");
  const auto run = test::run_pkm("plan " + program + " --machine " +
                                     test::source_path("examples/machines/hexapod_ch5.yaml") +
                                     " --dynamics --elastic --out " + out + " --json" + load,
                                 false);
  EXPECT_EQ(run.exit_code, 0) << run.out;
  if (run.exit_code != 0) return 0.0;
  return nlohmann::json::parse(run.out)["dynamics"]["max_dynamic_tool_error_mm"].get<double>();
}

TEST(ElasticLoad, ACuttingLoadAddsItsDeflectionToThePlannedRunsToolError) {
  const double unloaded = elastic_load_max_error_mm("");
  // 2 kN against the feed: the ch5 hexapod's 200 N/µm struts give way by about 20 µm in the plane.
  const double loaded = elastic_load_max_error_mm(" --load tangential=2000");
  EXPECT_GT(loaded, unloaded + 1e-3) << "unloaded " << unloaded << " mm, loaded " << loaded << " mm";
  EXPECT_LT(loaded, 0.1);
}

}  // namespace
}  // namespace pkm
