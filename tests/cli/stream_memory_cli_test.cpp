// pkm linuxcnc stream's and pkm interpolate's memory does not grow with the program: the plan is made while
// the program is read, and the interpolation's timing and strut laws follow it as windows. A program and one
// ten times as long: the longer run's peak resident memory (max RSS, from the kernel) stays within 20 % of
// the shorter's (what grows is the program reader's queue filling up to its bound; the whole plan held in
// memory took 3.3 times as much at 10 times the program).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/peak_memory_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

TEST(StreamMemory, TheExecutionStreamOfTenTimesTheProgramStaysWithinTwentyPercent) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_stream_memory_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string machine = test::source_path("examples/machines/hexapod_ch5.yaml");
  const std::string shorter = test::long_program(2000);
  const std::string longer = test::long_program(20000);
  // A 20 ms period: the same program, a twentieth of the periods of 1 ms.
  const auto stream = [&](const std::string& program, const std::string& to) {
    return test::run_pkm_measuring_memory(
        {"linuxcnc", "stream", "--machine", machine, program, "--to", to, "--period-ms", "20"});
  };
  const test::PeakMemory small = stream(shorter, (dir / "short.stream").string());
  const test::PeakMemory large = stream(longer, (dir / "long.stream").string());
  ASSERT_EQ(small.exit_code, 0);
  ASSERT_EQ(large.exit_code, 0);
  EXPECT_GT(fs::file_size(dir / "long.stream"), 8 * fs::file_size(dir / "short.stream"));
  EXPECT_LE(large.max_rss_kb, small.max_rss_kb * 12 / 10)
      << "max RSS " << small.max_rss_kb << " kB for 2000 lines, " << large.max_rss_kb << " kB for 20000";
  fs::remove_all(dir);
  fs::remove(shorter);
  fs::remove(longer);
}

}  // namespace
}  // namespace pkm
