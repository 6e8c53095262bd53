// Hot paths do not allocate (STYLE habit 3): IK, FK (warm, with and without a workspace), the Jacobian and
// the joint-angle and conditioning checks of every shipped machine, the servo-rate stream of a planned
// program (filter, path evaluation, IK per tick) and the periods of an interpolation run (the computation,
// its timing histogram, the contour measurement, the sinks' hand-over) run under a counting global operator
// new. This file owns the replacement for pkm_tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <new>
#include <random>

#include "core/units.hpp"
#include "dynamics/run_elastic.hpp"
#include "execution/step_executor.hpp"
#include "interpolation/interpolate_run.hpp"
#include "interpolation/methods/carrier_interpolator.hpp"
#include "interpolation/quantisation/discreteness_corrector.hpp"
#include "interpolation/quantisation/remainder_quantizer.hpp"
#include "machine/actuator_offsets.hpp"
#include "machine/hexapod.hpp"
#include "machine/joint_limits.hpp"
#include "pkmkins_bridge.h"
#include "planning/plan_test_support.hpp"
#include "servo/servo_simulator.hpp"
#include "statics/actuator_forces.hpp"
#include "stiffness/strut_compliance.hpp"
#include "test_support.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

// The replacements pair malloc with free on purpose; GCC cannot see that operator new here is that malloc.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
// Every replaceable allocation function is replaced, so that each pointer is allocated and freed by the same
// pair (a partial set would mix ours with the runtime's, which AddressSanitizer rightly reports).
void* counted_allocation(std::size_t size) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new(std::size_t size) {
  if (void* p = counted_allocation(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* p = counted_allocation(size)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return counted_allocation(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return counted_allocation(size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop

namespace pkm {
namespace {

// Through a volatile pointer: a new-expression whose result is unused may be elided (C++14), and whether
// GCC does depends on what else the unity batch inlines.
std::vector<int>* volatile g_allocation_sink = nullptr;

TEST(NoAllocation, CounterSeesAllocations) {
  const long before = g_allocations.load();
  g_allocation_sink = new std::vector<int>(100);
  delete g_allocation_sink;
  EXPECT_GE(g_allocations.load() - before, 2);
}

TEST(NoAllocation, KinematicsOfEveryShippedMachine) {
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_genhexkins.yaml", "hexapod_refined.yaml", "planar2.yaml", "planar3.yaml",
        "tripod.yaml", "tricept.yaml", "hexaglide.yaml", "triglide.yaml", "rotopod.yaml"}) {
    const Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *m.mechanism;
    PoseVector c = vector_from_pose(mech.convention(), mech.home());
    const AxisMask mask = mech.controlled_axes();
    for (int axis = 0; axis < 6; ++axis) {
      if (mask.controlled[axis]) c[axis] += axis < 3 ? 3.0 : 0.02;
    }
    const Pose target = *mech.complete_pose(pose_from_vector(mech.convention(), c));
    const auto q = mech.inverse(target);
    ASSERT_TRUE(q.ok()) << file;
    const long before = g_allocations.load();
    for (int i = 0; i < 10; ++i) {
      auto ik = mech.inverse(target);
      auto fk = mech.forward(*q, mech.home());
      auto j = mech.jacobian(target);
      ASSERT_TRUE(ik.ok() && fk.ok() && j.ok()) << file;
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << file;
  }
}

// `count` poses stepping away from home along every controlled coordinate (0.1 mm, 0.0005 rad a step),
// completed, with their actuator values: a short path on which the warm solvers are timed.
void noalloc_short_path(const Mechanism& mech, int count, std::vector<Pose>& poses,
                        std::vector<ActuatorVector>& values) {
  const AxisMask mask = mech.controlled_axes();
  for (int i = 0; i < count; ++i) {
    PoseVector c = vector_from_pose(mech.convention(), mech.home());
    for (int axis = 0; axis < 6; ++axis) {
      if (mask.controlled[axis]) c[axis] += (axis < 3 ? 0.1 : 0.0005) * i;
    }
    poses.push_back(*mech.complete_pose(pose_from_vector(mech.convention(), c)));
    values.push_back(*mech.inverse(poses.back()));
  }
}

// actuator_values_at from the pose's coordinates: the values of actuator_values at pose_from_vector of them,
// to rounding (the hexapod turns its joints by the elementary rotations instead of the matrix).
bool same_values_from_coordinates(const Mechanism& mech, const Pose& pose) {
  const PoseVector c = vector_from_pose(mech.convention(), pose);
  std::array<double, kMaxActuators> at{}, reference{};
  if (!mech.actuator_values_at(mech.convention(), c, at.data())) return false;
  if (!mech.actuator_values(pose_from_vector(mech.convention(), c), reference.data())) return false;
  for (int j = 0; j < mech.actuator_count(); ++j)
    if (!(std::abs(at[j] - reference[j]) <= 1e-12 * (1.0 + std::abs(reference[j])))) return false;
  return true;
}

// The servo-loop forms of the interface: warm FK with the mechanism's own workspace (made once, before the
// count), hot IK into caller storage, and the twist Jacobian, along a short path of every shipped machine.
TEST(NoAllocation, WarmForwardAndHotInverseOfEveryShippedMachine) {
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_genhexkins.yaml", "hexapod_refined.yaml", "planar2.yaml", "planar3.yaml",
        "tripod.yaml", "tricept.yaml", "hexaglide.yaml", "triglide.yaml", "rotopod.yaml"}) {
    const Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *m.mechanism;
    const int n = mech.actuator_count();
    const AxisMask mask = mech.controlled_axes();
    constexpr int kPoses = 20;
    std::vector<Pose> poses;
    std::vector<ActuatorVector> values;
    noalloc_short_path(mech, kPoses, poses, values);
    auto workspace = mech.make_fk_workspace();
    const FkOptions options;
    std::array<double, kMaxActuators> hot{};
    JacobianMatrix twist;
    TwistBasis basis;
    const long before = g_allocations.load();
    Pose previous = mech.home();
    for (int i = 0; i < kPoses; ++i) {
      auto fk = mech.forward_warm(values[i], previous, options, *workspace);
      ASSERT_TRUE(fk.ok()) << file << " pose " << i;
      previous = fk->pose;
      ASSERT_TRUE(mech.actuator_values(poses[i], hot.data())) << file;
      for (int j = 0; j < n; ++j) ASSERT_NEAR(hot[j], values[i][j], 1e-12) << file;
      ASSERT_TRUE(same_values_from_coordinates(mech, poses[i])) << file;
      ASSERT_TRUE(mech.twist_jacobian(poses[i], twist)) << file;
      ASSERT_EQ(twist.rows(), n);
      ASSERT_TRUE(mech.controlled_twists(poses[i], basis)) << file;
      ASSERT_EQ(basis.cols(), mask.count());
    }
    workspace->forget_path();
    workspace->reset();
    EXPECT_EQ(g_allocations.load() - before, 0) << file;
  }
}

// The drive-offset decorator (machine/actuator_offsets.hpp) on the servo-loop path: the readings plus the
// offsets are a fixed-capacity vector, and the inner mechanism's workspace is used as it is.
TEST(NoAllocation, WarmForwardAndHotInverseThroughActuatorOffsets) {
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_refined.yaml", "planar3.yaml", "tricept.yaml", "rotopod.yaml"}) {
    const Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    auto clone = m.mechanism->with_geometry(m.mechanism->geometry_parameters());
    ASSERT_TRUE(clone.ok()) << file;
    const int n = m.mechanism->actuator_count();
    ActuatorVector offsets(n);
    for (int j = 0; j < n; ++j)
      offsets[j] = (m.mechanism->actuators_are_angles() ? 1e-3 : 0.5) * (j % 2 ? 1 : -1);
    const auto decorated = with_actuator_offsets(std::move(clone.value()), offsets);
    const Mechanism& mech = *decorated;
    constexpr int kPoses = 20;
    std::vector<Pose> poses;
    std::vector<ActuatorVector> values;
    noalloc_short_path(mech, kPoses, poses, values);
    auto workspace = mech.make_fk_workspace();
    const FkOptions options;
    std::array<double, kMaxActuators> hot{};
    const long before = g_allocations.load();
    Pose previous = mech.home();
    for (int i = 0; i < kPoses; ++i) {
      auto fk = mech.forward_warm(values[i], previous, options, *workspace);
      ASSERT_TRUE(fk.ok()) << file << " pose " << i;
      ASSERT_LT((fk->pose.position_mm - poses[i].position_mm).norm(), 1e-7) << file << " pose " << i;
      previous = fk->pose;
      ASSERT_TRUE(mech.actuator_values(poses[i], hot.data())) << file;
      for (int j = 0; j < n; ++j) ASSERT_NEAR(hot[j], values[i][j], 1e-12) << file;
      ASSERT_TRUE(same_values_from_coordinates(mech, poses[i])) << file;
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << file;
  }
}

TEST(NoAllocation, JointAndConditioningLimitsOfEveryShippedMachine) {
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_genhexkins.yaml", "hexapod_refined.yaml", "planar2.yaml", "planar3.yaml",
        "tripod.yaml", "tricept.yaml", "hexaglide.yaml", "triglide.yaml", "rotopod.yaml"}) {
    Machine m = test::machine_from_example(std::string("examples/machines/") + file);
    // Limits every pose here satisfies, so that each check runs through all joints and the SVD.
    if (m.joint_axes.count > 0) {
      m.joint_limits.base_joint_max_rad = rad_from_deg(170);
      m.joint_limits.platform_joint_max_rad = rad_from_deg(170);
      m.joint_limits.update_cosines();
    }
    m.joint_limits.max_condition_number = 1e15;
    const Mechanism& mech = *m.mechanism;
    PoseVector c = vector_from_pose(mech.convention(), mech.home());
    const AxisMask mask = mech.controlled_axes();
    for (int axis = 0; axis < 6; ++axis) {
      if (mask.controlled[axis]) c[axis] += axis < 3 ? 3.0 : 0.02;
    }
    const Pose target = *mech.complete_pose(pose_from_vector(mech.convention(), c));
    const long before = g_allocations.load();
    for (int i = 0; i < 10; ++i) {
      const PassiveJointAngles angles = passive_joint_angles(m, target);
      const Status joints = check_joint_limits(m, target);
      const Status conditioning = check_conditioning_limit(m, target);
      ASSERT_TRUE(angles.count == m.joint_axes.count && joints.ok() && conditioning.ok()) << file;
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << file;
  }
}

TEST(NoAllocation, HexapodPathTrackingWithPlatformWorkspace) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto& h = dynamic_cast<const Hexapod&>(*m.mechanism);
  std::vector<ActuatorVector> lengths;
  for (int i = 0; i < 100; ++i) {
    Pose p = h.home();
    p.position_mm.x() += 0.1 * i;
    lengths.push_back(*h.inverse(p));
  }
  PlatformFkWorkspace<6> workspace;
  Pose previous = h.home();
  const FkOptions options;
  const long before = g_allocations.load();
  for (const auto& q : lengths) {
    auto fk = h.forward(q, previous, options, workspace);
    ASSERT_TRUE(fk.ok());
    previous = fk->pose;
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
}

TEST(NoAllocation, ServoStreamTicks) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(m, "G0 X-50 Y0 Z0\nG1 X50 F3000\nG2 X50 Y0 I-20 J0 A3\nM2\n");
  const auto plan = test::plan_or_fail(m, program);
  planning::ServoStream stream(plan, m);
  planning::ServoTick tick;
  ASSERT_TRUE(stream.next(tick));
  const long before = g_allocations.load();
  long ticks = 0;
  while (stream.next(tick)) ++ticks;
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(ticks, 1000);
  EXPECT_FALSE(stream.error().has_value());
}

// The executor of planned motion (execution/step_executor.hpp), as LinuxCNC's servo thread runs it: taking
// nominal periods and releasing servo periods through an override change, a hold and its release.
TEST(NoAllocation, StepExecutorPeriods) {
  execution::ExecutorSettings settings;
  settings.min_position_steps.fill(-1'000'000);
  settings.max_position_steps.fill(1'000'000);
  auto executor = std::make_unique<execution::StepExecutor>(settings);
  executor->start({});
  execution::NominalPeriod nominal;
  execution::ExecutedPeriod out;
  const long before = g_allocations.load();
  for (long k = 1; k <= 20000; ++k) {
    for (int j = 0; j < kMaxActuators; ++j) {
      nominal.ideal_steps[j] = 1000.0 * std::sin(1e-3 * static_cast<double>(k) + j);
      nominal.position_steps[j] = std::llround(nominal.ideal_steps[j]);
    }
    if (executor->has_room()) executor->push(nominal);
    executor->period({k < 5000 ? 1.0 : 0.6, k > 9000 && k < 12000, false}, out);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(out.tau_periods, 1000.0);
}

// The elastic machine along a planned run (dynamics::RunElastic, as `pkm plan --elastic`): after the first
// ticks (the model, the modes and the stepper made at the start), every tick's integration and response.
TEST(NoAllocation, ElasticResponseTicks) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(m, "G0 X-50 Y0 Z0\nG1 X50 F3000\nG2 X50 Y0 I-20 J0 A3\nM2\n");
  const auto plan = test::plan_or_fail(m, program);
  planning::ServoStream stream(plan, m);
  long responses = 0;
  auto run = dynamics::RunElastic::make(m, plan.period_s, [&responses](const dynamics::ElasticTick&) {
    ++responses;
    return ok_status();
  });
  ASSERT_TRUE(run.ok()) << run.error().message;
  planning::ServoTick tick;
  for (int k = 0; k < 5 && stream.next(tick); ++k)
    ASSERT_TRUE(run->add(tick.time_s, tick.line, tick.pose, tick.actuators).ok());
  const long before = g_allocations.load();
  while (stream.next(tick)) {
    if (!run->add(tick.time_s, tick.line, tick.pose, tick.actuators).ok()) break;
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  ASSERT_TRUE(run->finish().ok());
  EXPECT_GT(responses, 1000);
  EXPECT_EQ(responses, stream.tick_count());
}

TEST(NoAllocation, StaticsHexapodStrutForces) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch3.yaml");
  const auto& h = dynamic_cast<const Hexapod&>(*m.mechanism);
  const statics::Wrench load{Eigen::Vector3d(100, -50, -600), Eigen::Vector3d(1e3, 2e4, -5e3)};
  double forces[6];
  const long before = g_allocations.load();
  EXPECT_TRUE(statics::twist_actuator_forces(h, h.home(), load, forces));
  EXPECT_EQ(g_allocations.load() - before, 0);
}

// The strut-only compliance per path point (its bench goal: ≤ 1 µs on the hexapod).
TEST(NoAllocation, StrutComplianceOfEveryPoseAlongAPath) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto parameters = stiffness::strut_stiffness_of(m);
  ASSERT_TRUE(parameters.ok());
  auto warm = stiffness::strut_compliance(*m.mechanism, *parameters, m.mechanism->home());
  ASSERT_TRUE(warm.ok()) << warm.error().message;
  const long before = g_allocations.load();
  double trace = 0.0;
  for (int k = 0; k < 100; ++k) {
    const Pose pose = test::abc_pose(0.5 * k, -0.3 * k, 700, 0.05 * k, 0, 0.1 * k);
    auto compliance = stiffness::strut_compliance(*m.mechanism, *parameters, pose);
    if (compliance) trace += compliance->compliance.trace();
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(trace, 0.0);
}

// The real-time part of the interpolation (Smirnov 2019, §5.2.2): per period the carrier step (strut laws,
// chord check) and the quantisation, naive or corrected (two FK solves, two Jacobians, 64 combinations).
TEST(NoAllocation, InterpolationPeriods) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(m, "G0 X-50 Y0 Z0\nG1 X50 F3000\nG2 X50 Y0 I-20 J0 A3\nM2\n");
  const auto plan = test::plan_or_fail(m, program);
  auto timing = interpolation::IdealTiming::from_plan(plan, m);
  ASSERT_TRUE(timing.ok());
  for (bool fitted : {true, false}) {
    auto laws = fitted ? interpolation::StrutLaws::fit(m, plan.path, {}, "t.ngc")
                       : interpolation::StrutLaws::exact(m, plan.path, "t.ngc");
    ASSERT_TRUE(laws.ok());
    interpolation::CarrierSettings settings;
    interpolation::CarrierInterpolator carrier(*laws, *timing, settings);
    std::array<double, kMaxActuators> start{};
    ASSERT_TRUE(carrier.start(start).ok());
    const interpolation::ContourGauge gauge(m, plan.path);
    interpolation::CorrectorSettings corrector_settings;
    interpolation::DiscretenessCorrector corrector(m, plan.path, gauge, corrector_settings);
    ASSERT_TRUE(corrector.start(start).ok());
    interpolation::RemainderQuantizer remainder(6, 0.001);
    remainder.start(start);
    interpolation::CarrierPeriod period;
    interpolation::StepPeriod out;
    long periods = 0;
    const long before = g_allocations.load();
    while (carrier.next(period)) {
      ASSERT_TRUE(corrector.quantize(period, out).ok());
      remainder.quantize(period, out);
      ++periods;
    }
    EXPECT_EQ(g_allocations.load() - before, 0) << (fitted ? "fitted laws" : "exact laws");
    EXPECT_GT(periods, 1000);
    EXPECT_FALSE(carrier.error().has_value());
  }
}

// A sink that keeps nothing: what the run itself does per period, without a writer's buffers.
class NoAllocationCountingSink : public interpolation::StepSink {
 public:
  Status write(const interpolation::StepPeriod&) override {
    ++periods;
    return ok_status();
  }
  Status finish() override { return ok_status(); }
  long periods = 0;
};

// The whole loop of interpolate() between one period's hand-over and the next (the carrier step, the
// quantisation, the period-time histogram, the contour monitor, the sinks), after a warm-up of a few periods:
// a servo loop must not allocate (allocation is one of the causes to rule out in the worst period).
TEST(NoAllocation, InterpolateRunPeriodsAfterWarmUp) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto program = test::gcode_for(m, "G0 X-50 Y0 Z0\nG1 X50 F3000\nG2 X50 Y0 I-20 J0 A3\nM2\n");
  const auto plan = test::plan_or_fail(m, program);
  auto timing = interpolation::IdealTiming::from_plan(plan, m);
  ASSERT_TRUE(timing.ok());
  constexpr long kWarmUpPeriods = 2;
  for (const interpolation::Method method : {interpolation::Method::carrier_corrected,
                                             interpolation::Method::carrier, interpolation::Method::exact}) {
    long seen = 0;
    long at_last_period = 0;
    long allocations = 0;
    interpolation::InterpolateOptions options;
    options.method = method;
    options.on_period = [&](const interpolation::StepPeriod&, const interpolation::PeriodContour&,
                            const Eigen::Vector3d&) {
      const long now = g_allocations.load();
      if (seen >= kWarmUpPeriods) allocations += now - at_last_period;
      at_last_period = now;
      ++seen;
    };
    NoAllocationCountingSink sink;
    auto summary = interpolation::interpolate(m, plan.path, *timing, options, {&sink}, "t.ngc");
    const std::string name(interpolation::to_string(method));
    ASSERT_TRUE(summary.ok()) << name << ": " << summary.error().message;
    EXPECT_EQ(allocations, 0) << name;
    EXPECT_GT(seen, 1000) << name;
    EXPECT_EQ(sink.periods, seen) << name;
  }
}

}  // namespace
}  // namespace pkm

namespace pkm {
namespace {

// Every machine file of examples/machines, in name order.
std::vector<std::string> hotik_shipped_machines() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("examples/machines"))) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Poses from home to far out of reach: each controlled coordinate moved alone by small to absurd amounts,
// the pose that puts the first platform-side joint onto its base joint (a strut of zero length, up to
// rounding), and last a pose of NaNs (unreachable for every mechanism).
std::vector<Pose> hotik_probe_poses(const Mechanism& mech) {
  const PoseVector home = vector_from_pose(mech.convention(), mech.home());
  const AxisMask mask = mech.controlled_axes();
  std::vector<Pose> poses{mech.home()};
  for (int axis = 0; axis < 6; ++axis) {
    if (!mask.controlled[axis]) continue;
    const std::vector<double> steps = axis < 3 ? std::vector<double>{1.0, 50.0, 400.0, 3000.0, 1e5}
                                               : std::vector<double>{0.05, 0.8, 1.5, 3.0};
    for (double step : steps) {
      for (double sign : {-1.0, 1.0}) {
        PoseVector c = home;
        c[axis] += sign * step;
        poses.push_back(pose_from_vector(mech.convention(), c));
      }
    }
  }
  StrutJointPoints ends;
  if (mech.strut_ends(mech.home(), ends) > 0) {
    Pose folded = mech.home();
    folded.position_mm += ends.base_mm[0] - ends.platform_mm[0];
    poses.push_back(folded);
  }
  Pose nan = mech.home();
  nan.position_mm.setConstant(std::numeric_limits<double>::quiet_NaN());
  poses.push_back(nan);
  return poses;
}

// The hot inverse kinematics of every shipped machine allocates nothing, whether the pose is reachable or
// not (no message is built), and says what inverse() says: false where it fails, its values where not.
TEST(NoAllocation, HotInverseOfReachableAndUnreachablePosesOfEveryShippedMachine) {
  const std::vector<std::string> files = hotik_shipped_machines();
  ASSERT_GE(files.size(), 10u);
  for (const std::string& file : files) {
    const Machine m = test::machine_from_example("examples/machines/" + file);
    const Mechanism& mech = *m.mechanism;
    const int n = mech.actuator_count();
    const std::vector<Pose> poses = hotik_probe_poses(mech);
    std::vector<std::array<double, kMaxActuators>> values(poses.size());
    std::vector<char> reached(poses.size(), 0);
    const long before = g_allocations.load();
    for (std::size_t i = 0; i < poses.size(); ++i)
      reached[i] = mech.actuator_values(poses[i], values[i].data());
    EXPECT_EQ(g_allocations.load() - before, 0) << file;
    int reachable = 0, unreachable = 0;  // NaN pose aside
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const auto ik = mech.inverse(poses[i]);
      ASSERT_EQ(ik.ok(), reached[i] != 0)
          << file << " pose " << i << (ik.ok() ? "" : ": " + ik.error().message);
      if (!ik.ok()) {
        unreachable += i + 1 < poses.size();
        continue;
      }
      ++reachable;
      for (int j = 0; j < n; ++j)
        EXPECT_NEAR(values[i][static_cast<std::size_t>(j)], (*ik)[j],
                    1e-12 * std::max(1.0, std::abs((*ik)[j])))
            << file << " pose " << i << " actuator " << j + 1;
    }
    EXPECT_GT(reachable, 0) << file;
    EXPECT_FALSE(reached.back()) << file << ": the NaN pose";
    // Hexapods, planar machines and the symmetric tripod (whose yaw equation has a solution at any tilt)
    // reach every pose but those with a strut of zero length; the others have a reach of their own: the
    // guides, the carriage circle, the tricept's axis, the cardan joints' ±90°.
    const MechanismType type = mech.type();
    if (type == MechanismType::glide || type == MechanismType::rotopod || type == MechanismType::tricept ||
        type == MechanismType::hexapod_refined) {
      EXPECT_GT(unreachable, 0) << file;
    }
  }
}

// actuator_values and inverse agree on random poses about home (±100 mm, ±15° on the controlled
// coordinates), per mechanism: the same values where inverse() succeeds, false where it fails.
TEST(HotInverse, AgreesWithInverseOnRandomPosesOfEveryShippedMachine) {
  for (const std::string& file : hotik_shipped_machines()) {
    const Machine m = test::machine_from_example("examples/machines/" + file);
    const Mechanism& mech = *m.mechanism;
    const int n = mech.actuator_count();
    const PoseVector home = vector_from_pose(mech.convention(), mech.home());
    const AxisMask mask = mech.controlled_axes();
    std::mt19937_64 random(20261126);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int reachable = 0;
    for (int k = 0; k < 300; ++k) {
      PoseVector c = home;
      for (int axis = 0; axis < 6; ++axis) {
        if (mask.controlled[axis]) c[axis] += unit(random) * (axis < 3 ? 100.0 : rad_from_deg(15.0));
      }
      const auto pose = mech.complete_pose(pose_from_vector(mech.convention(), c));
      if (!pose) continue;
      std::array<double, kMaxActuators> hot{};
      const bool reached = mech.actuator_values(*pose, hot.data());
      const auto ik = mech.inverse(*pose);
      ASSERT_EQ(ik.ok(), reached) << file << " pose " << k;
      if (!ik.ok()) continue;
      ++reachable;
      for (int j = 0; j < n; ++j)
        ASSERT_NEAR(hot[static_cast<std::size_t>(j)], (*ik)[j], 1e-12 * std::max(1.0, std::abs((*ik)[j])))
            << file << " pose " << k << " actuator " << j + 1;
    }
    EXPECT_GE(reachable, 50) << file;
  }
}

TEST(NoAllocation, ServoLoopPeriods) {
  servo::LoopDesign design;
  design.drives = 6;
  for (int j = 0; j < 6; ++j) {
    servo::ChannelGains& g = design.channels[j];
    g.lag_s = 1e-3;
    g.inertia = 0.05;
    g.force_per_command = 3000.0;
    g.command_max = 9000.0;
    g.error_max = 2.0;
    g.speed_gain = g.inertia / (2.0 * g.lag_s);
    g.position_gain_per_s = 250.0;
  }
  servo::ServoSimulator simulator(design, 2.5e-4);
  simulator.reset(servo::DriveVector::Constant(500.0));
  servo::DriveVector reference = servo::DriveVector::Constant(500.0),
                     rate = servo::DriveVector::Constant(20.0);
  const long before = g_allocations.load();
  for (int k = 0; k < 1000; ++k) {
    reference += rate * 2.5e-4;
    simulator.step(reference, rate);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_TRUE(simulator.finite());
}

}  // namespace
}  // namespace pkm

namespace pkm {
namespace {

// LinuxCNC's pkmkins module (linuxcnc/pkmkins_bridge.h) calls the bridge's inverse and forward kinematics in
// the servo thread: along a path of small steps, after one warm-up call, neither allocates.
TEST(NoAllocation, PkmkinsBridgeInverseAndForwardAlongAPath) {
  for (const char* file :
       {"hexapod_ch5.yaml", "hexapod_genhexkins.yaml", "hexapod_refined.yaml", "tripod.yaml",
        "hexaglide.yaml", "triglide.yaml", "rotopod.yaml", "tricept.yaml", "planar3.yaml", "planar2.yaml"}) {
    SCOPED_TRACE(file);
    char error[512] = "";
    const std::string path = test::source_path(std::string("examples/machines/") + file);
    pkmkins_machine* m = pkmkins_load(path.c_str(), error, sizeof error);
    ASSERT_NE(m, nullptr) << error;
    const std::string coordinates = pkmkins_coordinates(m);
    double home[6];
    double joints[6];
    ASSERT_EQ(pkmkins_home(m, home, joints), 0);
    // 100 poses stepping 0.05 mm / 0.01 deg a pose along every controlled coordinate.
    std::vector<std::array<double, 6>> poses(100);
    for (std::size_t k = 0; k < poses.size(); ++k) {
      for (int i = 0; i < 6; ++i) {
        const bool controlled = coordinates.find("XYZABC"[i]) != std::string::npos;
        poses[k][static_cast<std::size_t>(i)] =
            home[i] + (controlled ? (i < 3 ? 0.05 : 0.01) * static_cast<double>(k + 1) : 0.0);
      }
    }
    double world[6];
    ASSERT_EQ(pkmkins_inverse(m, poses[0].data(), joints), 0);
    ASSERT_EQ(pkmkins_forward(m, joints, world), 0);
    const long before = g_allocations.load();
    for (std::size_t k = 1; k < poses.size(); ++k) {
      ASSERT_EQ(pkmkins_inverse(m, poses[k].data(), joints), 0) << "pose " << k;
      ASSERT_EQ(pkmkins_forward(m, joints, world), 0) << "pose " << k;
    }
    EXPECT_EQ(g_allocations.load() - before, 0);
    // Non-finite input fails before any solve, without allocating either.
    double nan_joints[6];
    std::copy(joints, joints + 6, nan_joints);
    nan_joints[0] = std::numeric_limits<double>::quiet_NaN();
    double nan_pose[6];
    std::copy(home, home + 6, nan_pose);
    // A coordinate the machine controls (the others do not enter its IK).
    nan_pose[std::string("XYZABC").find(coordinates[0])] = std::numeric_limits<double>::quiet_NaN();
    const long before_failures = g_allocations.load();
    EXPECT_EQ(pkmkins_forward(m, nan_joints, world), -1);
    EXPECT_EQ(pkmkins_inverse(m, nan_pose, joints), -1);
    EXPECT_EQ(g_allocations.load() - before_failures, 0);
    pkmkins_free(m);
  }
  // Joints no pose has (struts of 1 mm): Newton fails in the servo thread, without allocating.
  char error[512] = "";
  const std::string path = test::source_path("examples/machines/hexapod_ch5.yaml");
  pkmkins_machine* m = pkmkins_load(path.c_str(), error, sizeof error);
  ASSERT_NE(m, nullptr) << error;
  const double short_struts[6] = {1, 1, 1, 1, 1, 1};
  double world[6];
  const long before = g_allocations.load();
  EXPECT_EQ(pkmkins_forward(m, short_struts, world), -1);
  EXPECT_EQ(g_allocations.load() - before, 0);
  pkmkins_free(m);
}

}  // namespace
}  // namespace pkm
