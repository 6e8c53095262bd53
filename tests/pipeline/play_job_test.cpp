// `pkm play` as a library call (pipeline/play_job.hpp): a stream in a directory is played whole, each
// period passed on as the steps.csv row the CSV writer gives it, and a missing stream is refused naming it.
#include "pipeline/play_job.hpp"

#include <gtest/gtest.h>

#include <string>

#include "interpolation/drive_output/step_stream.hpp"
#include "interpolation/drive_output/steps_csv.hpp"
#include "interpolation/step_test_support.hpp"

namespace pkm {
namespace {

TEST(PlayJob, PlaysADirectorysStreamAndPassesEachPeriodOnAsACsvRow) {
  const test::StepTempDir dir;
  const interpolation::StepStreamHeader header = test::step_header(6, 0.0005);
  interpolation::StepStreamWriter binary;
  interpolation::StepsCsvWriter csv;
  ASSERT_TRUE(binary.open(interpolation::step_stream_path(dir.path().string()), header));
  ASSERT_TRUE(csv.open(interpolation::steps_csv_path(dir.path().string()), header));
  for (const auto& p : test::random_periods(header, 40, 43U)) {
    ASSERT_TRUE(binary.write(p));
    ASSERT_TRUE(csv.write(p));
  }
  ASSERT_TRUE(binary.finish());
  ASSERT_TRUE(csv.finish());
  pipeline::PlayJob job;
  job.input = dir.path().string();
  job.to = dir.file("played.csv");
  auto played = pipeline::run_play_job(job);
  ASSERT_TRUE(played) << played.error().message;
  EXPECT_EQ(played->path, interpolation::step_stream_path(dir.path().string()));
  EXPECT_EQ(played->period_count, 40);
  EXPECT_EQ(played->statistics.periods, 40);
  EXPECT_EQ(played->header.actuators, 6);
  EXPECT_EQ(test::read_bytes(dir.file("played.csv")),
            test::read_bytes(interpolation::steps_csv_path(dir.path().string())));
}

TEST(PlayJob, RefusesAMissingStreamNamingIt) {
  const test::StepTempDir dir;
  pipeline::PlayJob job;
  job.input = dir.file("nothing.bin");
  auto played = pipeline::run_play_job(job);
  ASSERT_FALSE(played);
  EXPECT_NE(played.error().message.find("nothing.bin"), std::string::npos) << played.error().message;
}

}  // namespace
}  // namespace pkm
