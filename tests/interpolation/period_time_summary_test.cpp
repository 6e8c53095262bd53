// The run summary's per-period compute-time distribution: its keys exist, one sample per period,
// the percentiles ordered. No time is asserted: the machine running the tests is not ours to time.
#include <gtest/gtest.h>

#include "formats/interpolation_summary.hpp"
#include "interpolation/interpolation_test_support.hpp"

namespace pkm {
namespace {

TEST(PeriodTimeSummary, DistributionOfEveryCarrierMethodIsCompleteAndOrdered) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const planning::MotionPlan plan = test::ch5_line_plan(machine, 0.001);
  auto timing = interpolation::IdealTiming::from_plan(plan, machine);
  ASSERT_TRUE(timing.ok()) << timing.error().message;
  for (const interpolation::Method method : {interpolation::Method::exact, interpolation::Method::carrier,
                                             interpolation::Method::carrier_corrected}) {
    interpolation::InterpolateOptions options;
    options.method = method;
    options.period_s = 0.001;
    const auto summary = test::interpolate_or_fail(machine, plan.path, *timing, options);
    const std::string name(interpolation::to_string(method));
    const DurationDistribution& time = summary.period_time;
    EXPECT_EQ(time.count, summary.periods) << name;
    EXPECT_GT(time.p50_us, 0.0) << name;
    EXPECT_LE(time.p50_us, time.p99_us) << name;
    EXPECT_LE(time.p99_us, time.p99_9_us) << name;
    EXPECT_LE(time.p99_9_us, time.max_us) << name;
    EXPECT_LE(time.over_budget, time.count) << name;

    const nlohmann::json json = formats::interpolation_summary_json(summary, machine);
    for (const char* key :
         {"period_time_count", "period_time_us_p50", "period_time_us_p99", "period_time_us_p99_9",
          "period_time_us_max", "period_time_us_mean", "period_time_over_10us"}) {
      EXPECT_TRUE(json.contains(key)) << name << ": " << key;
    }
    EXPECT_EQ(json["period_time_count"].get<long>(), json["periods"].get<long>()) << name;
    EXPECT_LE(json["period_time_us_p50"].get<double>(), json["period_time_us_p99"].get<double>()) << name;
    EXPECT_LE(json["period_time_us_p99"].get<double>(), json["period_time_us_p99_9"].get<double>()) << name;
    EXPECT_LE(json["period_time_us_p99_9"].get<double>(), json["period_time_us_max"].get<double>()) << name;
    EXPECT_DOUBLE_EQ(json["period_time_us_max"].get<double>(),
                     json["max_compute_us_per_period"].get<double>())
        << name;
  }
}

}  // namespace
}  // namespace pkm
