// The calibration jobs' parameters are checked in the library, for every caller: a value outside a
// parameter's range is refused with the parameter's name before anything runs or is written, and every value
// inside it passes the check.
#include "pipeline/calibration_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace pkm {
namespace {

// The job's field that each range guards, set to `value` in an otherwise valid job.
struct CalibrationField {
  pipeline::ParameterRange range;
  void (*set)(pipeline::CalibrationSimulateJob&, double);
};

std::vector<CalibrationField> calibration_fields() {
  using Job = pipeline::CalibrationSimulateJob;
  return {
      {pipeline::kCalibrationPoses, [](Job& j, double v) { j.plan.poses = static_cast<int>(v); }},
      {pipeline::kCalibrationBoxMm, [](Job& j, double v) { j.plan.box_mm = v; }},
      {pipeline::kCalibrationBoxDeg, [](Job& j, double v) { j.plan.box_deg = v; }},
      {pipeline::kCalibrationStrutChangeMm, [](Job& j, double v) { j.plan.strut_change_mm = v; }},
      {pipeline::kCalibrationCandidates, [](Job& j, double v) { j.plan.candidates = static_cast<int>(v); }},
      {pipeline::kCalibrationHeldOut, [](Job& j, double v) { j.plan.held_out = static_cast<int>(v); }},
      {pipeline::kCalibrationPlateRadiusMm, [](Job& j, double v) { j.instrument.plate_radius_mm = v; }},
      {pipeline::kCalibrationSigmaMm, [](Job& j, double v) { j.instrument.sigma_mm = v; }},
      {pipeline::kCalibrationTrials, [](Job& j, double v) { j.trials = static_cast<int>(v); }},
      {pipeline::kCalibrationJointErrorMm, [](Job& j, double v) { j.joint_error_mm = v; }},
      {pipeline::kCalibrationOffsetErrorMm, [](Job& j, double v) { j.offset_error_mm = v; }},
  };
}

// A valid job: the defaults with a pose count (0, the default, is the seven-pose plan's own count only).
pipeline::CalibrationSimulateJob valid_calibration_job() {
  pipeline::CalibrationSimulateJob job;
  job.plan.poses = 12;
  return job;
}

TEST(CalibrationChecks, ValuesOutsideARangeAreRefusedByNameAndValuesInsidePass) {
  std::mt19937 random(11);
  ASSERT_TRUE(pipeline::check_calibration_simulate_job(valid_calibration_job()).ok());
  for (const CalibrationField& field : calibration_fields()) {
    const pipeline::ParameterRange& r = field.range;
    std::uniform_real_distribution<double> inside(r.low, r.high);
    for (int k = 0; k < 20; ++k) {
      double value = inside(random);
      if (r.whole) value = std::round(value);
      if (!r.low_inclusive && value <= r.low) continue;
      pipeline::CalibrationSimulateJob job = valid_calibration_job();
      field.set(job, value);
      EXPECT_TRUE(pipeline::check_calibration_simulate_job(job).ok()) << r.name << " " << value;
    }
    const double span = r.high - r.low;
    for (double outside :
         {r.high + 0.5 * span + 1.0, r.low - 0.5 * span - 1.0, r.low_inclusive ? r.low - 1 : r.low}) {
      pipeline::CalibrationSimulateJob job = valid_calibration_job();
      field.set(job, outside);
      const Status checked = pipeline::check_calibration_simulate_job(job);
      ASSERT_FALSE(checked.ok()) << r.name << " " << outside;
      EXPECT_EQ(checked.error().code, ErrorCode::bad_input);
      EXPECT_EQ(checked.error().message.rfind(std::string(r.name) + " ", 0), 0u) << checked.error().message;
    }
  }
}

TEST(CalibrationChecks, TheSevenPosePlanAloneMayLeaveItsCountToTheMethod) {
  pipeline::CalibrationPlanSpec spec;
  spec.poses = 0;
  spec.method = pipeline::CalibrationPlanMethod::seven_pose;
  EXPECT_TRUE(pipeline::check_calibration_plan_spec(spec).ok());
  spec.method = pipeline::CalibrationPlanMethod::random;
  EXPECT_FALSE(pipeline::check_calibration_plan_spec(spec).ok());
}

TEST(CalibrationChecks, ABallbarMeasuresNoFixtureAndNoiseIsOffOnlyForAFile) {
  pipeline::CalibrationInstrument ballbar;
  ballbar.ballbar_centre_mm = Eigen::Vector3d(0, 0, 500);
  EXPECT_TRUE(pipeline::check_calibration_instrument(ballbar).ok());
  ballbar.fixture_path = "targets.csv";
  EXPECT_FALSE(pipeline::check_calibration_instrument(ballbar).ok());
  pipeline::CalibrationSimulateJob job = valid_calibration_job();
  job.noise = false;
  EXPECT_FALSE(pipeline::check_calibration_simulate_job(job).ok());
  job.measurements_path = "m.csv";
  EXPECT_TRUE(pipeline::check_calibration_simulate_job(job).ok());
}

TEST(CalibrationChecks, TheHoldoutIsAWholeCountOfPoses) {
  pipeline::CalibrationIdentifyJob job;
  job.holdout = -1;
  EXPECT_FALSE(pipeline::check_calibration_identify_job(job).ok());
  job.holdout = 3;
  EXPECT_TRUE(pipeline::check_calibration_identify_job(job).ok());
}

}  // namespace
}  // namespace pkm
