// Where to put the sheet (Smirnov 2019, §3.8.1, Fig. 120): the drive energy of one forming path at a range
// of heights. The work of the load along the path does not depend on where the path lies; the drives never
// spend less than it; on the seeds' V7 hexapod the energy changes more than twofold between z1 = 300 and
// 700 mm.
#include "redundancy/placement_study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "planning/plan_test_support.hpp"
#include "program/spif_path.hpp"
#include "redundancy_test_support.hpp"

namespace pkm::test {
namespace {

// The seeds' forming loads (Aerens et al. 2009 for DC01, 1.15 mm): axial 2500 N, tangential 1400 N, radial
// 350 N, on a punch of 25 mm diameter.
statics::LoadModel seeds_load() {
  auto load = statics::parse_load_spec("axial=2500,tangential=1400,normal=350,cutter_radius=12.5");
  EXPECT_TRUE(load) << load.error().message;
  return *load;
}

program::CanonicalProgram spif_program(const Machine& machine, const program::SpifPathOptions& options) {
  auto text = program::spif_program_text(options);
  EXPECT_TRUE(text);
  return gcode_for(machine, *text, "spif.ngc");
}

redundancy::PlacementOptions heights(std::vector<double> z1_mm, double step_mm = 2.0) {
  redundancy::PlacementOptions options;
  options.z1_mm = std::move(z1_mm);
  options.step_mm = step_mm;
  options.loads = seeds_load();
  return options;
}

// The largest relative difference of the load's work between the placements.
double work_spread(const std::vector<redundancy::Placement>& placements) {
  double low = 1e300, high = -1e300;
  for (const auto& p : placements)
    low = std::min(low, p.required_work_J), high = std::max(high, p.required_work_J);
  return (high - low) / high;
}

// On the ch3 hexapod without its weights, random cones at random heights: the work of the load is the same
// wherever the path lies, up to the strut lengths' curvature over a step (ΔL = J Δx + O(Δx²/L), so the
// difference falls with the step), the drives' energy is never below it, and the planes' energies add up to
// the feed moves' share of the total.
TEST(PlacementStudy, TheLoadsWorkDoesNotDependOnWhereThePathLies) {
  const Machine machine = machine_from_text(ch3_hexapod_text(20.0), "ch3_hexapod.yaml");
  std::mt19937 random(1208);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    program::SpifPathOptions o;
    o.planes = 3 + static_cast<int>(5 * unit(random));
    o.radius_mm = 30.0 + 50.0 * unit(random);
    o.radius_step_mm = unit(random);
    o.counter_clockwise = unit(random) < 0.5;
    o.kind = unit(random) < 0.5 ? program::SpifPathKind::helix : program::SpifPathKind::planes;
    const auto program = spif_program(machine, o);
    const double low = 500.0 + 80.0 * unit(random);
    const std::vector<double> z1{low, low + 60.0, low + 120.0};
    auto placements = redundancy::placement_study(program, machine, heights(z1, 1.0));
    auto finer = redundancy::placement_study(program, machine, heights(z1, 0.25));
    ASSERT_TRUE(placements) << placements.error().message;
    ASSERT_TRUE(finer) << finer.error().message;
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    EXPECT_LT(work_spread(*placements), 2e-3);
    EXPECT_LT(work_spread(*finer), 0.5 * work_spread(*placements));
    for (const auto& p : *placements) {
      ASSERT_TRUE(p.feasible) << p.z1_mm;
      EXPECT_GE(p.energy_J, p.required_work_J * (1.0 - 1e-9));
      // A helix's plunge to the first plane ends above its first turn: a plane of its own.
      ASSERT_EQ(static_cast<int>(p.planes.size()),
                o.planes + (o.kind == program::SpifPathKind::helix ? 1 : 0));
      double planes_J = 0.0;
      for (const auto& plane : p.planes) planes_J += plane.energy_J;
      EXPECT_LE(planes_J, p.energy_J * (1.0 + 1e-12));
      EXPECT_GT(planes_J, 0.99 * p.energy_J);  // the retract carries no load
    }
    // The placements differ in what the drives spend, not in what the load takes.
    EXPECT_GT(std::abs(placements->front().energy_J / placements->back().energy_J - 1.0),
              10.0 * work_spread(*placements));
  }
}

// The seeds' case (§3.8.1) on the V7 hexapod with its weights: between a first plane at z1 = 300 and at 700
// mm the drive energy changes by more than twice. On this machine the lower placement costs more (its struts
// lie flatter); the seeds' own machine, whose geometry they do not give, had it the other way round.
TEST(PlacementStudy, TheSeedsCaseChangesTheEnergyMoreThanTwofold) {
  const Machine machine = machine_from_example("examples/machines/hexapod_ch3.yaml");
  const auto program = spif_program(machine, {});
  auto placements = redundancy::placement_study(program, machine, heights({300, 400, 500, 600, 700}));
  ASSERT_TRUE(placements) << placements.error().message;
  ASSERT_EQ(placements->size(), 5u);
  for (std::size_t i = 0; i < placements->size(); ++i) {
    ASSERT_TRUE((*placements)[i].feasible);
    ASSERT_EQ((*placements)[i].planes.size(), 21u);
    if (i > 0) {
      EXPECT_LT((*placements)[i].energy_J, (*placements)[i - 1].energy_J);
    }
  }
  EXPECT_GT(placements->front().energy_J / placements->back().energy_J, 2.0);
  // Every plane's energy at z1 = 300 is more than twice that at 700 (Fig. 120's curves do not cross).
  for (std::size_t n = 0; n < 21; ++n)
    EXPECT_GT(placements->front().planes[n].energy_J, 2.0 * placements->back().planes[n].energy_J) << n;
}

TEST(PlacementStudy, OutOfReachHeightsAreMarkedAndMachinesWithoutAnglesRefused) {
  // The ch5 hexapod's struts reach 350 … 900 mm; program Z0 is its home tool point.
  const Machine machine = machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = spif_program(machine, {});
  auto placements = redundancy::placement_study(program, machine, heights({0, 1000}));
  ASSERT_TRUE(placements) << placements.error().message;
  EXPECT_TRUE((*placements)[0].feasible);
  EXPECT_FALSE((*placements)[1].feasible);
  EXPECT_GT((*placements)[1].first_infeasible_line, 0);
  const Machine tripod = machine_from_example("examples/machines/tripod.yaml");
  auto refused = redundancy::placement_study(spif_program(tripod, {}), tripod, heights({0}));
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("holds the platform's angles"), std::string::npos)
      << refused.error().message;
}

// The seeds' second lever (§3.8.1, Fig. 123): the energy law over the three angles within ψ, ϑ ±5°, γ ±20°,
// the angles returned to zero at each plane. Between two returns it never costs more than holding the angles,
// so neither does the whole path.
TEST(PlacementStudy, TheEnergyLawWithItsResetsNeverCostsMoreThanHolding) {
  const Machine machine = machine_from_example("examples/machines/hexapod_ch3.yaml");
  program::SpifPathOptions path;
  path.planes = 4;
  const auto program = spif_program(machine, path);
  auto options = heights({400, 700});
  options.law = redundancy::Law::energy;
  options.law_bounds_deg = {{-5.0, 5.0}, {-5.0, 5.0}, {-20.0, 20.0}};
  auto placements = redundancy::placement_study(program, machine, options);
  ASSERT_TRUE(placements) << placements.error().message;
  for (const auto& p : *placements) {
    ASSERT_TRUE(p.feasible);
    ASSERT_FALSE(std::isnan(p.law_energy_J));
    EXPECT_LE(p.law_energy_J, p.energy_J * (1.0 + 1e-12)) << p.z1_mm;
    EXPECT_GE(p.law_energy_J, p.required_work_J * (1.0 - 1e-9)) << p.z1_mm;
    double planes_J = 0.0;
    // (A plane's own figure holds the return of the angles at its start, which the plane before chose.)
    for (const auto& plane : p.planes) planes_J += plane.law_energy_J;
    EXPECT_LE(planes_J, p.law_energy_J * (1.0 + 1e-12));
  }
  // Without a law the law's figures are not there.
  auto held = redundancy::placement_study(program, machine, heights({700}));
  ASSERT_TRUE(held);
  EXPECT_TRUE(std::isnan(held->front().law_energy_J));
  EXPECT_TRUE(std::isnan(held->front().planes.front().law_energy_J));
  // Bounds for two of the three angles are refused, naming them.
  options.law_bounds_deg = {{-5.0, 5.0}, {-5.0, 5.0}};
  auto refused = redundancy::placement_study(program, machine, options);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("2 ranges"), std::string::npos) << refused.error().message;
}

}  // namespace
}  // namespace pkm::test
