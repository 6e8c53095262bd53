// The machine in the loop (servo/coupled_machine.hpp): the drives' servo loops closed on the elastic
// machine. Checked by its physics: the power balance (the drives' and the load's work = the change of the
// kinetic, elastic and gravity energies + what friction and damping dissipate, to 10⁻⁶) on random moves,
// loads, frictions and gaps; at rest it stays at rest; the rigid servo simulation is its limit as the
// struts stiffen, and the drives become position sources (the elastic response to the prescribed motion)
// as the loops get fast.
#include "servo/coupled_machine.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/elastic_simulation.hpp"
#include "io/machine_file.hpp"
#include "servo/servo_plant.hpp"
#include "servo/servo_simulator.hpp"
#include "test_support.hpp"

namespace pkm::servo {
namespace {

Machine ch5_machine() {
  return test::machine_from_example("examples/machines/hexapod_ch5.yaml");
}

// The drives' loops of `machine`, tuned for the inertia at home.
LoopDesign design_at_home(const Machine& machine) {
  auto inertia = machine_inertia(machine, machine.mechanism->home());
  EXPECT_TRUE(inertia);
  const int n = machine.mechanism->actuator_count();
  ActuatorVector a = inertia->diagonal().head(n) + motor_inertia(machine.servo, n);
  auto design = design_loops(machine, a);
  EXPECT_TRUE(design) << design.error().message;
  return *design;
}

DriveVector drives_at(const Machine& machine, const Pose& pose) {
  DriveVector out = DriveVector::Zero();
  EXPECT_TRUE(machine.mechanism->actuator_values(pose, out.data()));
  return out;
}

DriveVector home_drives(const Machine& machine) {
  return drives_at(machine, machine.mechanism->home());
}

// A smooth move of the platform from home by `offset` (mm, x y z) in `duration_s`: the drives' set points
// and speeds at t (central difference).
struct PoseMove {
  const Machine* machine;
  Eigen::Vector3d offset;
  Eigen::Vector3d tilt_rad = Eigen::Vector3d::Zero();
  double duration_s = 0.1;
  DriveVector at(double t) const {
    const double u = std::clamp(t / duration_s, 0.0, 1.0), s = u * u * (3.0 - 2.0 * u);
    Pose pose = machine->mechanism->home();
    pose.position_mm += s * offset;
    pose.rotation = pose.rotation * Eigen::AngleAxisd(s * tilt_rad.norm(), tilt_rad.norm() > 0.0
                                                                               ? tilt_rad.normalized()
                                                                               : Eigen::Vector3d::UnitZ())
                                        .toRotationMatrix();
    return drives_at(*machine, pose);
  }
  DriveVector speed(double t) const { return (at(t + 1e-6) - at(t - 1e-6)) / 2e-6; }
};

// Runs `machine` through `move` for `duration_s`; returns the energies at the end.
CoupledEnergy run_move(CoupledMachine& coupled, const PoseMove& move, double duration_s) {
  const double h = coupled.loop_period_s();
  const int periods = static_cast<int>(std::lround(duration_s / h));
  for (int k = 0; k < periods; ++k) {
    const double t = k * h;
    const Status stepped = coupled.step(move.at(t), move.speed(t));
    EXPECT_TRUE(stepped) << stepped.error().message;
    if (!stepped) break;
  }
  auto energy = coupled.energy();
  EXPECT_TRUE(energy);
  return *energy;
}

TEST(CoupledMachine, AtRestStaysAtRestHoldingGravity) {
  const Machine machine = ch5_machine();
  const LoopDesign design = design_at_home(machine);
  auto coupled = CoupledMachine::make(machine, design, 2.5e-4);
  ASSERT_TRUE(coupled) << coupled.error().message;
  const DriveVector q = home_drives(machine);
  ASSERT_TRUE(coupled->reset(0.0, q, machine.mechanism->home()));
  const Pose start = coupled->pose();
  // The sag under gravity is a few µm, downwards.
  EXPECT_LT(start.position_mm.z(), machine.mechanism->home().position_mm.z());
  EXPECT_GT(start.position_mm.z(), machine.mechanism->home().position_mm.z() - 0.05);
  for (int k = 0; k < 4000; ++k) ASSERT_TRUE(coupled->step(q, DriveVector::Zero()));
  // The technical optimum's loops are P only: each drive holds its force F with the static error
  // e = F / (K_w k_p) (the speed regulator's force K_w · k_p e), and then stands still.
  for (int j = 0; j < 6; ++j) {
    const ChannelGains& g = design.channels[j];
    const double droop = coupled->force()[j] / (g.speed_gain * g.position_gain_per_s);
    EXPECT_NEAR(q[j] - coupled->position()[j], droop, 1e-3 * std::abs(droop) + 1e-9) << "drive " << j;
    EXPECT_LT(std::abs(coupled->speed()[j]), 1e-6);
    EXPECT_GT(coupled->force()[j], 0.0);  // the struts push the platform up
  }
}

// The power balance on random moves, loads, frictions, gaps and transmissions, integrated tightly.
TEST(CoupledMachine, DriveAndLoadWorkEqualStoredPlusDissipatedEnergy) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    Machine machine = ch5_machine();
    for (int j = 0; j < 6; ++j) {
      DriveServo& d = machine.servo.drives[j];
      d.friction_coulomb = 20.0 + 10.0 * unit(random);
      d.friction_static = d.friction_coulomb * 1.5;
      d.stribeck_speed = 1.0;
      d.friction_viscous = 0.5 + 0.4 * unit(random);
      d.backlash = trial % 2 == 1 ? 0.002 : 0.0;
      d.transmission_stiffness = trial >= 2 ? 150000.0 : 0.0;
    }
    const LoopDesign design = [&] {
      LoopDesign d = design_at_home(machine);
      for (int j = 0; j < 6; ++j) {
        d.channels[j].friction_coulomb = machine.servo.drives[j].friction_coulomb;
        d.channels[j].friction_static = machine.servo.drives[j].friction_static;
        d.channels[j].stribeck_speed = machine.servo.drives[j].stribeck_speed;
        d.channels[j].friction_viscous = machine.servo.drives[j].friction_viscous;
        d.channels[j].backlash = machine.servo.drives[j].backlash;
      }
      return d;
    }();
    CoupledOptions options;
    options.track_energy = true;
    options.integration.abs_tolerance_mm = 1e-11;
    options.integration.rel_tolerance = 1e-12;
    auto coupled = CoupledMachine::make(machine, design, 2.5e-4, options);
    ASSERT_TRUE(coupled) << coupled.error().message;
    statics::Wrench load;
    load.force_N = Eigen::Vector3d(unit(random), unit(random), unit(random)) * 300.0;
    load.moment_Nmm = Eigen::Vector3d(unit(random), unit(random), unit(random)) * 5000.0;
    ASSERT_TRUE(coupled->reset(0.0, home_drives(machine), machine.mechanism->home(), load));
    auto before = coupled->energy();
    ASSERT_TRUE(before);
    const PoseMove move{&machine, Eigen::Vector3d(unit(random), unit(random), unit(random)) * 5.0,
                        Eigen::Vector3d(unit(random), unit(random), unit(random)) * 0.02, 0.1};
    const CoupledEnergy after = run_move(*coupled, move, 0.15);
    const double stored = after.stored_J() - before->stored_J();
    const double balance = after.input_J - stored - after.dissipated_J;
    const double scale = std::abs(after.input_J) + after.dissipated_J + std::abs(stored);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << ": input " << after.input_J << " J, stored "
                                      << stored << " J, dissipated " << after.dissipated_J << " J");
    EXPECT_GT(after.dissipated_J, 0.0);
    EXPECT_GT(scale, 1e-3);
    EXPECT_LT(std::abs(balance), 1e-6 * scale);
  }
}

}  // namespace
}  // namespace pkm::servo

namespace pkm::servo {
namespace {

// The largest difference between the drives' positions of two runs of the same move, and the largest
// following error of the first.
struct RunDifference {
  double drives_mm = 0.0;
  double following_mm = 0.0;
};

// Every strut's stiffness (and no transmission in series) set to `stiffness_N_mm`.
Machine ch5_with_stiffness(double stiffness_N_mm) {
  Machine machine = ch5_machine();
  for (int j = 0; j < 6; ++j) {
    machine.dynamics.struts[j].stiffness_N_mm = stiffness_N_mm;
    machine.servo.drives[j].transmission_stiffness = machine.servo.drives[j].transmission_damping = 0.0;
  }
  return machine;
}

// The coupled machine against the rigid plant (servo_simulator.hpp: the machine's inertia at home and the
// motors', the load the drives hold at rest) on the same move, ideal drives.
RunDifference coupled_against_rigid(double stiffness_N_mm) {
  const Machine machine = ch5_with_stiffness(stiffness_N_mm);
  const LoopDesign design = design_at_home(machine);
  const double h = 2.5e-4;
  auto coupled = CoupledMachine::make(machine, design, h);
  EXPECT_TRUE(coupled);
  const DriveVector start = home_drives(machine);
  EXPECT_TRUE(coupled->reset(0.0, start, machine.mechanism->home()));
  ServoSimulator rigid(design, h);
  auto inertia = machine_inertia(machine, machine.mechanism->home());
  EXPECT_TRUE(inertia);
  DriveMatrix a = *inertia;
  a.diagonal().head(6) += motor_inertia(machine.servo, 6);
  DriveMatrix inverse = DriveMatrix::Zero();
  inverse.topLeftCorner(6, 6) = a.topLeftCorner(6, 6).inverse();
  rigid.set_inverse_inertia(inverse);
  rigid.set_load(coupled->force());
  rigid.reset(start);
  // A short move: the rigid plant holds the inertia and the load of home, which a long one would leave.
  const PoseMove move{&machine, Eigen::Vector3d(0.6, -0.4, 0.2), Eigen::Vector3d::Zero(), 0.1};
  RunDifference out;
  for (int k = 0; k < 600; ++k) {
    const double t = k * h;
    EXPECT_TRUE(coupled->step(move.at(t), move.speed(t)));
    rigid.step(move.at(t), move.speed(t));
    out.drives_mm = std::max(out.drives_mm, (coupled->position() - rigid.position()).cwiseAbs().maxCoeff());
    out.following_mm = std::max(out.following_mm, (move.at(t + h) - rigid.position()).cwiseAbs().maxCoeff());
  }
  return out;
}

TEST(CoupledMachine, StifferStrutsTendToTheRigidServoSimulation) {
  const RunDifference soft = coupled_against_rigid(2e5), stiff = coupled_against_rigid(2e6),
                      stiffest = coupled_against_rigid(2e7);
  SCOPED_TRACE(::testing::Message() << soft.drives_mm << " " << stiff.drives_mm << " " << stiffest.drives_mm
                                    << " mm; following " << soft.following_mm << " mm");
  // What is left at 2·10⁷ N/mm is the rigid plant's own simplification (the inertia and the load of home,
  // no velocity terms): a fifth of a percent of the following error.
  EXPECT_LT(stiff.drives_mm, 0.5 * soft.drives_mm);
  EXPECT_LT(stiffest.drives_mm, 0.7 * stiff.drives_mm);
  EXPECT_LT(stiffest.drives_mm, 0.005 * stiffest.following_mm);
}

// The platform's largest distance from the elastic response to the prescribed motion (the drives as
// position sources, dynamics/elastic_simulation.hpp) when the loops' current lag is `lag_s`.
double coupled_against_prescribed(double lag_s) {
  Machine machine = ch5_machine();
  for (int j = 0; j < 6; ++j) {
    machine.servo.drives[j].current_time_constant_s = lag_s;
    // The prescribed motion's model has the struts alone.
    machine.servo.drives[j].transmission_stiffness = machine.servo.drives[j].transmission_damping = 0.0;
  }
  machine.servo.velocity_feedforward = 1.0;
  const LoopDesign design = design_at_home(machine);
  const double h = lag_s / 4.0;
  auto coupled = CoupledMachine::make(machine, design, h);
  EXPECT_TRUE(coupled);
  EXPECT_TRUE(coupled->reset(0.0, home_drives(machine), machine.mechanism->home()));
  auto model = dynamics::make_elastic_model(machine);
  EXPECT_TRUE(model);
  // The prescribed run starts where the coupled one rests (its drives sag with the P loops' static error).
  struct Prescribed final : dynamics::DriveMotion {
    PoseMove move;
    DriveVector offset;
    void setpoint(double t, dynamics::DriveSetpoint& out) const override {
      out.position_mm = (move.at(t) - offset).head(6);
      out.rate_mm_s = move.speed(t).head(6);
    }
  } prescribed;
  prescribed.move = PoseMove{&machine, Eigen::Vector3d(3.0, -2.0, 1.0), Eigen::Vector3d::Zero(), 0.1};
  prescribed.offset = home_drives(machine) - coupled->position();
  dynamics::ElasticSimulator elastic(*model);
  EXPECT_TRUE(elastic.start(0.0, coupled->pose(), dynamics::CoordinateVector::Zero(6)));
  double largest = 0.0;
  const int periods = static_cast<int>(std::lround(0.15 / h));
  for (int k = 0; k < periods; ++k) {
    const double t = k * h;
    EXPECT_TRUE(coupled->step(prescribed.move.at(t), prescribed.move.speed(t)));
    EXPECT_TRUE(elastic.advance_to(t + h, prescribed));
    largest = std::max(largest, (coupled->pose().position_mm - elastic.pose().position_mm).norm());
  }
  return largest;
}

TEST(CoupledMachine, FasterLoopsTendToTheElasticResponseToThePrescribedMotion) {
  // The loops hold the motors' masses still against the struts' vibration (556 Hz) only once their
  // bandwidth is well above it.
  const double slow = coupled_against_prescribed(1e-3), fast = coupled_against_prescribed(1e-4),
               fastest = coupled_against_prescribed(1e-5);
  SCOPED_TRACE(::testing::Message() << slow << " " << fast << " " << fastest << " mm");
  EXPECT_LT(fast, 0.5 * slow);
  EXPECT_LT(fastest, 0.3 * fast);
  EXPECT_LT(fastest, 0.02 * slow);
}

}  // namespace
}  // namespace pkm::servo

namespace pkm::servo {
namespace {

std::string example_text(const std::string& file) {
  std::ifstream in(test::source_path("examples/machines/" + file));
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

constexpr const char* kServoSection = R"(
servo:
  tuning: technical_optimum
  loop_period_ms: 0.25
  drives: {current_time_constant_ms: 1.0, base_speed_mm_s: 500, base_force_N: 3000, motor_inertia_kg_cm2: 0.8,
           screw_lead_mm: 10, transmission_stiffness_N_mm: 300000, transmission_damping_N_s_per_mm: 3,
           friction_coulomb_N: 15, friction_static_N: 20, stribeck_speed_mm_s: 2, friction_viscous_N_s_per_mm: 0.3}
)";

// The other kinds of machine the elastic model moves: a planar one and a glide machine (constant struts on
// carriages), each with drives added; the power balance holds on random moves of each.
TEST(CoupledMachine, PlanarAndGlideMachinesBalanceTheirPowerToo) {
  const std::string glide_dynamics = R"(
dynamics:
  platform: {mass_kg: 40, com_mm: [0, 0, 100], inertia_kg_m2: [0.4, 0.4, 0.4]}
  struts:
    lower: {mass_kg: 6, com_mm: 400, inertia_kg_m2: 0.3}
    stiffness_N_mm: 150000
    damping: {model: viscous, coefficient: 5}
    carriage_kg: 10
)";
  const std::vector<std::pair<Machine, Eigen::Vector3d>> machines = [&] {
    std::vector<std::pair<Machine, Eigen::Vector3d>> out;
    out.emplace_back(test::machine_from_text(example_text("planar2.yaml") + kServoSection, "planar2.yaml"),
                     Eigen::Vector3d(1.0, 1.0, 0.0));
    out.emplace_back(test::machine_from_text(example_text("hexaglide.yaml") + glide_dynamics + kServoSection,
                                             "glide.yaml"),
                     Eigen::Vector3d(1.0, 1.0, 1.0));
    return out;
  }();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const auto& [machine, axes] : machines) {
    SCOPED_TRACE(machine.source);
    const int n = machine.mechanism->actuator_count();
    auto inertia = machine_inertia(machine, machine.mechanism->home());
    ASSERT_TRUE(inertia) << inertia.error().message;
    auto design = design_loops(machine, inertia->diagonal().head(n) + motor_inertia(machine.servo, n));
    ASSERT_TRUE(design) << design.error().message;
    CoupledOptions options;
    options.track_energy = true;
    options.integration.abs_tolerance_mm = 1e-11;
    options.integration.rel_tolerance = 1e-12;
    auto coupled = CoupledMachine::make(machine, *design, 2.5e-4, options);
    ASSERT_TRUE(coupled) << coupled.error().message;
    for (int trial = 0; trial < 2; ++trial) {
      ASSERT_TRUE(coupled->reset(0.0, home_drives(machine), machine.mechanism->home()));
      auto before = coupled->energy();
      ASSERT_TRUE(before);
      const PoseMove move{&machine,
                          Eigen::Vector3d(unit(random), unit(random), unit(random)).cwiseProduct(axes) * 4.0,
                          Eigen::Vector3d::Zero(), 0.1};
      const CoupledEnergy after = run_move(*coupled, move, 0.15);
      const double stored = after.stored_J() - before->stored_J();
      const double scale = std::abs(after.input_J) + after.dissipated_J + std::abs(stored);
      EXPECT_GT(after.dissipated_J, 0.0);
      EXPECT_LT(std::abs(after.input_J - stored - after.dissipated_J), 1e-6 * scale);
    }
  }
}

}  // namespace
}  // namespace pkm::servo

namespace pkm::servo {
namespace {

// The tripod's platform is not free (its twist basis is constrained) and the rotopod's drives are angular:
// both are refused, saying why and naming the machine file.
TEST(CoupledMachine, MachinesWithoutAFreePlatformModelAreRefusedSayingWhy) {
  for (const char* file : {"tripod.yaml", "rotopod.yaml"}) {
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    ASSERT_TRUE(machine.servo.given()) << file;
    LoopDesign design;
    design.drives = machine.mechanism->actuator_count();
    for (int j = 0; j < design.drives; ++j) design.channels[j].lag_s = 1e-3;
    auto coupled = CoupledMachine::make(machine, design, 2.5e-4);
    ASSERT_FALSE(coupled) << file;
    EXPECT_NE(coupled.error().message.find(file), std::string::npos) << coupled.error().message;
  }
}

}  // namespace
}  // namespace pkm::servo
