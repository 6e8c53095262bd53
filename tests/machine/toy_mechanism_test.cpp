// A mechanism that exists only here: a three-axis Cartesian gantry (actuator j moves the tool along base axis
// j). It implements Mechanism and nothing else, so planning and interpolation running on it show that those
// stages need only the interface: no cast to a concrete mechanism, no test of the type.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "interpolation/interpolation_test_support.hpp"

namespace pkm {
namespace {

class ToyGantry final : public Mechanism {
 public:
  explicit ToyGantry(const Eigen::Vector3d& home_mm) { home_.position_mm = home_mm; }

  // A label only: no stage may branch on it (a branch would send the gantry down the glide's path).
  MechanismType type() const override { return MechanismType::glide; }
  int actuator_count() const override { return 3; }
  AngleConvention convention() const override { return AngleConvention::abc; }
  AxisMask controlled_axes() const override { return AxisMask::translations(); }

  Result<Pose> complete_pose(const Pose& pose) const override { return Pose{pose.position_mm, kNoTurn}; }
  Result<ActuatorVector> inverse(const Pose& pose) const override {
    ActuatorVector q(3);
    q = pose.position_mm;
    return q;
  }
  bool actuator_values(const Pose& pose, double* out) const noexcept override {
    for (int j = 0; j < 3; ++j) out[j] = pose.position_mm[j];
    return true;
  }
  Result<FkSolution> forward(const ActuatorVector& actuators, const Pose& /*guess*/,
                             const FkOptions& /*options*/ = {}) const override {
    FkSolution solution;
    solution.pose = Pose{actuators.head<3>(), kNoTurn};
    return solution;
  }
  Result<JacobianMatrix> jacobian(const Pose& /*pose*/) const override {
    return JacobianMatrix(Eigen::Matrix3d::Identity());
  }
  /// Carriage rates are the tool's velocity; turning the tool moves no carriage (the ω columns are zero).
  bool twist_jacobian(const Pose& /*pose*/, JacobianMatrix& out) const noexcept override {
    out.setZero(3, 6);
    out.leftCols<3>().setIdentity();
    return true;
  }
  MechanismStructure structure() const override { return {"3-P (gantry)", false, 4, {3, 0, 0, 0, 0}, 0}; }

 private:
  inline static const Eigen::Matrix3d kNoTurn = Eigen::Matrix3d::Identity();
};

Machine toy_machine() {
  Machine machine;
  machine.source = "toy_mechanism_test.cpp";
  machine.name = "toy gantry";
  machine.mechanism = std::make_unique<ToyGantry>(Eigen::Vector3d(100.0, 100.0, 100.0));
  machine.limits.min = 0.0;
  machine.limits.max = 300.0;
  machine.limits.speed = 200.0;
  machine.limits.accel = 2000.0;
  return machine;
}

// Records every period's steps, as a drive would receive them.
class ToyRecordingSink : public interpolation::StepSink {
 public:
  std::vector<interpolation::StepPeriod> periods;
  Status write(const interpolation::StepPeriod& period) override {
    periods.push_back(period);
    return ok_status();
  }
  Status finish() override { return ok_status(); }
};

TEST(ToyMechanism, PlansAndInterpolatesThroughTheInterfaceOnly) {
  const Machine machine = toy_machine();
  const auto program = test::gcode_for(machine, "G1 X150 Y120 Z100 F3000\nG2 X150 Y80 I0 J-20\nG1 Z80\nM2\n");
  planning::PlanOptions plan_options;
  plan_options.rate_hz = 1000.0;
  const planning::MotionPlan plan = test::plan_or_fail(machine, program, plan_options);
  ASSERT_FALSE(plan.path.segments.empty());
  auto timing = interpolation::IdealTiming::from_plan(plan, machine);
  ASSERT_TRUE(timing.ok()) << timing.error().message;

  for (interpolation::Method method :
       {interpolation::Method::exact, interpolation::Method::carrier,
        interpolation::Method::carrier_corrected, interpolation::Method::estimating}) {
    SCOPED_TRACE(std::string(interpolation::to_string(method)));
    interpolation::InterpolateOptions options;
    options.method = method;
    options.period_s = 0.001;
    options.step_mm = 0.001;
    ToyRecordingSink sink;
    const auto summary = test::interpolate_or_fail(machine, plan.path, *timing, options, {&sink});
    ASSERT_EQ(summary.actuators, 3);
    ASSERT_EQ(static_cast<long>(sink.periods.size()), summary.periods);
    ASSERT_GT(summary.periods, 100);
    // Positions are the start plus the running sum of the steps; no drive ever takes more than the summary's
    // largest step count in one period.
    std::array<std::int64_t, kMaxActuators> position = summary.start_position;
    for (const auto& period : sink.periods) {
      for (int j = 0; j < 3; ++j) {
        position[j] += period.steps[j];
        ASSERT_EQ(position[j], period.position[j]);
        ASSERT_LE(std::abs(period.steps[j]), summary.max_steps_per_period);
      }
    }
    if (method == interpolation::Method::estimating) {
      // The estimating function keeps the tool within its own allowed deviation δ (its tacts, not the
      // period ends, follow the path), and stops within δ of the end.
      const double deviation_mm = options.estimating.deviation_mm;
      EXPECT_LE(summary.contour.max_error_after_first_mm, deviation_mm + options.step_mm);
      EXPECT_LE(summary.contour.end_error_mm, deviation_mm);
    } else {
      // The path ends exactly: every drive within one step of the ideal end.
      for (int j = 0; j < 3; ++j) {
        EXPECT_LE(std::abs(position[j] * options.step_mm - summary.ideal_end[j]), options.step_mm) << j;
      }
      // Each axis stays within one step of its ideal position, which is on the path within ρ_max: the tool
      // is within √3 steps + ρ_max of the path.
      const double bound_mm = std::sqrt(3.0) * options.step_mm + options.rho_max_mm;
      EXPECT_LE(summary.contour.max_error_after_first_mm, bound_mm);
      EXPECT_LE(summary.contour.end_error_mm, std::sqrt(3.0) * options.step_mm);
    }
    EXPECT_EQ(summary.contour.fk_failures, 0);
  }
}

TEST(ToyMechanism, WarmForwardKinematicsUsesTheDefaultWorkspace) {
  const ToyGantry toy(Eigen::Vector3d(10.0, 20.0, 30.0));
  auto workspace = toy.make_fk_workspace();
  ASSERT_NE(workspace, nullptr);
  ActuatorVector q(3);
  q << 11.0, 22.0, 33.0;
  auto solution = toy.forward_warm(q, toy.home(), FkOptions{}, *workspace);
  ASSERT_TRUE(solution.ok());
  EXPECT_EQ(solution->pose.position_mm, Eigen::Vector3d(11.0, 22.0, 33.0));
  EXPECT_FALSE(toy.is_planar());
  EXPECT_FALSE(toy.has_distance_actuators());
}

}  // namespace
}  // namespace pkm
