// pkm play from the command line: a stream written by the library is played in full or in part, its
// periods passed on as steps.csv rows, and a missing or damaged file exits 2 naming the file.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_support.hpp"
#include "interpolation/drive_output/step_stream.hpp"
#include "interpolation/drive_output/steps_csv.hpp"
#include "interpolation/step_test_support.hpp"

namespace pkm {
namespace {

void write_stream_and_csv(const test::StepTempDir& dir, long count) {
  const interpolation::StepStreamHeader header = test::step_header(6, 0.001);
  interpolation::StepStreamWriter binary;
  interpolation::StepsCsvWriter csv;
  ASSERT_TRUE(binary.open(interpolation::step_stream_path(dir.path().string()), header));
  ASSERT_TRUE(csv.open(interpolation::steps_csv_path(dir.path().string()), header));
  for (const auto& p : test::random_periods(header, count, 41U)) {
    ASSERT_TRUE(binary.write(p));
    ASSERT_TRUE(csv.write(p));
  }
  ASSERT_TRUE(binary.finish());
  ASSERT_TRUE(csv.finish());
}

TEST(PlayCli, PlaysADirectoryAndPrintsJson) {
  const test::StepTempDir dir;
  write_stream_and_csv(dir, 60);
  const auto run = test::run_pkm("play " + dir.path().string() + " --json", false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto stats = nlohmann::json::parse(run.out);
  for (const char* key : {"periods", "max_lateness_us", "mean_lateness_us", "p99_lateness_us", "overruns",
                          "memory_locked", "realtime_priority", "wall_time_s", "period_s"}) {
    EXPECT_TRUE(stats.contains(key)) << key;
  }
  EXPECT_EQ(stats["periods"].get<long>(), 60);
  EXPECT_DOUBLE_EQ(stats["period_s"].get<double>(), 0.001);
  EXPECT_GE(stats["wall_time_s"].get<double>(), 0.059);
  EXPECT_GE(stats["max_lateness_us"].get<double>(), stats["mean_lateness_us"].get<double>());
}

TEST(PlayCli, PassesThePeriodsOnAsCsvRows) {
  const test::StepTempDir dir;
  write_stream_and_csv(dir, 40);
  const std::string out = dir.file("played.csv");
  const auto run = test::run_pkm("play " + dir.file("steps.bin") + " --to " + out + " --realtime");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("played            40 periods"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("SCHED_FIFO"), std::string::npos) << run.out;
  EXPECT_EQ(test::read_bytes(out), test::read_bytes(dir.file("steps.csv")));

  const auto part = test::run_pkm("play " + dir.path().string() + " --periods 5 --to - --json", false);
  ASSERT_EQ(part.exit_code, 0) << part.out;
  const std::string csv = test::read_bytes(dir.file("steps.csv"));
  std::size_t end = 0;
  for (int line = 0; line < 6; ++line) end = csv.find('\n', end) + 1;
  EXPECT_EQ(part.out, csv.substr(0, end));  // the header and five rows; the statistics went to stderr
}

TEST(PlayCli, MissingOrCorruptFilesExitWithTwo) {
  const test::StepTempDir dir;
  const auto missing = test::run_pkm("play " + dir.file("nothing.bin"));
  EXPECT_EQ(missing.exit_code, 2) << missing.out;
  EXPECT_NE(missing.out.find("nothing.bin"), std::string::npos) << missing.out;

  write_stream_and_csv(dir, 30);
  std::string bytes = test::read_bytes(dir.file("steps.bin"));
  test::write_bytes(dir.file("pkm_play_corrupt.bin"), bytes.substr(0, bytes.size() - 3));
  const auto truncated = test::run_pkm("play " + dir.file("pkm_play_corrupt.bin"));
  EXPECT_EQ(truncated.exit_code, 2) << truncated.out;
  EXPECT_NE(
      truncated.out.find("pkm play: error: " + dir.file("pkm_play_corrupt.bin") + ": truncated at byte"),
      std::string::npos)
      << truncated.out;

  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x01);
  test::write_bytes(dir.file("steps.bin"), bytes);
  const auto corrupt = test::run_pkm("play " + dir.path().string());
  EXPECT_EQ(corrupt.exit_code, 2) << corrupt.out;
  EXPECT_NE(corrupt.out.find(dir.file("steps.bin") + ": corrupt at byte"), std::string::npos) << corrupt.out;
}

}  // namespace
}  // namespace pkm
