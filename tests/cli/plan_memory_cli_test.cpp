// pkm plan's memory does not grow with the program: the whole command (reading, planning, the ticks and
// ticks.h5) on a program and on one ten times as long, its peak resident memory (max RSS, from the kernel)
// within 10 % of the shorter run's.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/peak_memory_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

test::PeakMemory plan_and_measure(const std::string& program, const std::string& out_dir) {
  const std::string machine = test::source_path("examples/machines/hexapod_ch5.yaml");
  return test::run_pkm_measuring_memory(
      {"plan", "--machine", machine, program, "--out", out_dir, "--max-ticks", "1000000000"});
}

TEST(PlanMemory, PeakMemoryOfTenTimesTheProgramStaysWithinTenPercent) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_memory_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string shorter = test::long_program(4000);
  const std::string longer = test::long_program(40000);
  const test::PeakMemory small = plan_and_measure(shorter, (dir / "short").string());
  const test::PeakMemory large = plan_and_measure(longer, (dir / "long").string());
  ASSERT_EQ(small.exit_code, 0);
  ASSERT_EQ(large.exit_code, 0);
  EXPECT_GT(fs::file_size(dir / "long" / "ticks.h5"), 5 * fs::file_size(dir / "short" / "ticks.h5"));
  EXPECT_LE(large.max_rss_kb, small.max_rss_kb * 11 / 10)
      << "max RSS " << small.max_rss_kb << " kB for 4000 lines, " << large.max_rss_kb << " kB for 40000";
  fs::remove_all(dir);
  fs::remove(shorter);
  fs::remove(longer);
}

}  // namespace
}  // namespace pkm
