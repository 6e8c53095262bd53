// The real-time player: every period released in order at its deadline, never early, statistics that add
// up, and a clean stop on a failing sink. No upper bounds on time: the machine running the tests is shared.
#include "interpolation/drive_output/realtime_player.hpp"

#include <gtest/gtest.h>
#include <time.h>

#include <string>
#include <vector>

#include "interpolation/step_test_support.hpp"

namespace pkm::interpolation {
namespace {

// Remembers what arrives and when (storage reserved up front, so the sink itself does not allocate).
class RecordingSink : public StepSink {
 public:
  explicit RecordingSink(std::size_t capacity) {
    periods.reserve(capacity);
    times_ns.reserve(capacity);
  }
  Status write(const StepPeriod& period) override {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    times_ns.push_back(std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec);
    periods.push_back(period);
    if (fail_at >= 0 && period.index == fail_at) return make_error(ErrorCode::io, "the drive went away");
    return ok_status();
  }
  Status finish() override {
    ++finished;
    return ok_status();
  }
  std::vector<StepPeriod> periods;
  std::vector<std::int64_t> times_ns;
  int finished = 0;
  long fail_at = -1;
};

std::string write_test_stream(const test::StepTempDir& dir, int actuators, long count, double period_s,
                              std::vector<StepPeriod>* written = nullptr) {
  const StepStreamHeader header = test::step_header(actuators, period_s);
  const auto periods = test::random_periods(header, count, 31U);
  StepStreamWriter writer;
  const std::string path = dir.file("steps.bin");
  EXPECT_TRUE(writer.open(path, header));
  for (const StepPeriod& p : periods) EXPECT_TRUE(writer.write(p));
  EXPECT_TRUE(writer.finish());
  if (written) *written = periods;
  return path;
}

TEST(RealtimePlayer, Plays200PeriodsAt1kHzInOrderAndNeverEarly) {
  const test::StepTempDir dir;
  std::vector<StepPeriod> expected;
  const std::string path = write_test_stream(dir, 6, 200, 0.001, &expected);
  StepStreamReader reader;
  ASSERT_TRUE(reader.open(path));
  RecordingSink sink(200);
  auto played = play(reader, sink, {});
  ASSERT_TRUE(played) << played.error().message;
  EXPECT_EQ(played->periods, 200);
  EXPECT_EQ(sink.finished, 1);
  test::expect_same_periods(sink.periods, expected, 6);
  for (std::size_t k = 1; k < sink.times_ns.size(); ++k) EXPECT_GE(sink.times_ns[k], sink.times_ns[k - 1]);
  // Deadlines t0 + k·h: every period reaches the sink at or after its own deadline (exact, on the same
  // clock; the lateness histogram is only within 3 %, and the sink's clock read comes after the player's).
  ASSERT_EQ(sink.times_ns.size(), 200U);
  for (std::size_t k = 0; k < sink.times_ns.size(); ++k) {
    EXPECT_GE(sink.times_ns[k], played->first_deadline_ns + static_cast<std::int64_t>(k) * 1'000'000) << k;
  }
  EXPECT_GE(played->wall_time_s, 0.199);
  EXPECT_GE(played->min_lateness_us, 0.0);  // clock_nanosleep never wakes before the deadline
  EXPECT_GE(played->mean_lateness_us, played->min_lateness_us);
  EXPECT_GE(played->max_lateness_us, played->mean_lateness_us);
  EXPECT_GE(played->p99_lateness_us, 0.0);
  EXPECT_LE(played->p99_lateness_us, played->max_lateness_us);
  // The distribution: ordered, one sample per released period, the overruns are its periods over h.
  const DurationDistribution& lateness = played->lateness;
  EXPECT_EQ(lateness.count, 200);
  EXPECT_LE(lateness.p50_us, lateness.p99_us);
  EXPECT_LE(lateness.p99_us, lateness.p99_9_us);
  EXPECT_LE(lateness.p99_9_us, lateness.max_us);
  EXPECT_DOUBLE_EQ(lateness.max_us, played->max_lateness_us);
  EXPECT_EQ(lateness.over_budget, played->overruns);
  EXPECT_GE(played->overruns, 0);
  EXPECT_LE(played->overruns, 200);
  EXPECT_FALSE(played->memory_locked);
  EXPECT_FALSE(played->realtime_priority);
}

TEST(RealtimePlayer, StopsAfterMaxPeriodsAndFinishesTheSink) {
  const test::StepTempDir dir;
  const std::string path = write_test_stream(dir, 3, 50, 0.0005);
  StepStreamReader reader;
  ASSERT_TRUE(reader.open(path));
  RecordingSink sink(50);
  PlayerSettings settings;
  settings.max_periods = 10;
  auto played = play(reader, sink, settings);
  ASSERT_TRUE(played) << played.error().message;
  EXPECT_EQ(played->periods, 10);
  EXPECT_EQ(sink.periods.size(), 10U);
  EXPECT_EQ(sink.periods.back().index, 9);
  EXPECT_EQ(sink.finished, 1);
  EXPECT_GE(played->wall_time_s, 9 * 0.0005);
}

TEST(RealtimePlayer, AskingForRealtimeNeverFails) {
  const test::StepTempDir dir;
  const std::string path = write_test_stream(dir, 6, 20, 0.001);
  StepStreamReader reader;
  ASSERT_TRUE(reader.open(path));
  RecordingSink sink(20);
  PlayerSettings settings;
  settings.try_realtime = true;
  auto played = play(reader, sink, settings);
  ASSERT_TRUE(played) << played.error().message;
  EXPECT_EQ(played->periods, 20);
  // Granted or not (usually not in a container), nothing else changes.
  RecordProperty("memory_locked", played->memory_locked ? "yes" : "no");
  RecordProperty("realtime_priority", played->realtime_priority ? "yes" : "no");
}

TEST(RealtimePlayer, AFailingSinkStopsThePlayWithoutFinishing) {
  const test::StepTempDir dir;
  const std::string path = write_test_stream(dir, 3, 50, 0.0002);
  StepStreamReader reader;
  ASSERT_TRUE(reader.open(path));
  RecordingSink sink(50);
  sink.fail_at = 5;
  auto played = play(reader, sink, {});
  ASSERT_FALSE(played);
  EXPECT_EQ(played.error().message, "the drive went away");
  EXPECT_EQ(sink.periods.size(), 6U);
  EXPECT_EQ(sink.finished, 0);
}

TEST(RealtimePlayer, ThePeriodCanBeOverridden) {
  const test::StepTempDir dir;
  const std::string path = write_test_stream(dir, 1, 30, 0.01);
  StepStreamReader reader;
  ASSERT_TRUE(reader.open(path));
  RecordingSink sink(30);
  PlayerSettings settings;
  settings.period_s = 0.0001;  // a hundred times the stream's rate: a dry run
  auto played = play(reader, sink, settings);
  ASSERT_TRUE(played) << played.error().message;
  EXPECT_EQ(played->periods, 30);
  EXPECT_GE(played->wall_time_s, 29 * 0.0001);
  settings.period_s = -1.0;
  EXPECT_FALSE(play(reader, sink, settings));
}

}  // namespace
}  // namespace pkm::interpolation
