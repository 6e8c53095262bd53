// What pkm plan tells its progress sink (core/progress.hpp): the phases in order, each one's fraction in
// [0, 1] and never going back, the lines those of the program, and the writing told through to its end, with
// the ticks written counting up to the run's.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/machine_file.hpp"
#include "pipeline/plan_program.hpp"
#include "source_paths.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

int line_count(const std::string& program) {
  std::ifstream in(test::source_path("examples/programs/" + program));
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines;
}

struct Told {
  std::string phase;
  double fraction;
  int line;
  long ticks;
};

std::vector<Told> plan_and_listen(const std::string& program, const std::string& name, bool report,
                                  long* run_ticks = nullptr) {
  auto machine = load_machine_file(test::source_path("examples/machines/hexapod_ch5.yaml"));
  EXPECT_TRUE(machine) << machine.error().message;
  std::vector<Told> told;
  pipeline::PlanJob job;
  job.program_path = test::source_path("examples/programs/" + program);
  job.out_directory = (fs::temp_directory_path() / ("pkm_plan_progress_" + name)).string();
  fs::remove_all(job.out_directory);
  if (report) job.report_path = job.out_directory + "/report.html";
  job.progress = [&](const ProgressStep& step) {
    told.push_back({std::string(step.phase), step.fraction, step.line, step.ticks});
  };
  auto result = pipeline::plan_program(*machine, job);
  EXPECT_TRUE(result) << result.error().message;
  if (result && run_ticks != nullptr) *run_ticks = result->summary["ticks"].get<long>();
  return told;
}

void expect_honest_progress(const std::vector<Told>& told, int program_lines, bool report) {
  const std::vector<std::string> order = {
      "reading the program", "building the tool path", "planning",
      "timing the motion",   "writing the outputs",    "writing the report"};
  ASSERT_FALSE(told.empty());
  std::size_t at = 0;
  double last_fraction = -1.0;
  bool wrote_to_the_end = false;
  for (const Told& step : told) {
    const auto found = std::find(order.begin() + static_cast<long>(at), order.end(), step.phase);
    ASSERT_NE(found, order.end()) << "unknown phase, or one out of order: " << step.phase;
    const auto index = static_cast<std::size_t>(found - order.begin());
    if (index != at) last_fraction = -1.0;
    at = index;
    EXPECT_LE(step.fraction, 1.0) << step.phase;
    if (step.fraction >= 0.0) {
      EXPECT_GE(step.fraction, last_fraction) << step.phase << " went back";
      last_fraction = step.fraction;
    }
    EXPECT_GE(step.line, 0);
    EXPECT_LE(step.line, program_lines) << step.phase;
    if (step.phase == "writing the outputs" && step.fraction == 1.0) wrote_to_the_end = true;
  }
  EXPECT_EQ(told.front().phase, "reading the program");
  EXPECT_TRUE(wrote_to_the_end);
  EXPECT_EQ(told.back().phase, report ? "writing the report" : "writing the outputs");
}

TEST(PlanProgress, PhasesInOrderFractionsForwardLinesOfTheProgram) {
  // The report's phase where this build has the report page (a build without Node.js refuses --report).
  constexpr bool report = PKM_REPORT_PAGE;
  expect_honest_progress(plan_and_listen("pocket.ngc", "pocket", report), line_count("pocket.ngc"), report);
  expect_honest_progress(plan_and_listen("helix.ngc", "helix", false), line_count("helix.ngc"), false);
}

TEST(PlanProgress, TheWritingCountsTheTicksUpToTheRuns) {
  long run_ticks = 0;
  const std::vector<Told> told = plan_and_listen("helix.ngc", "helix_ticks", false, &run_ticks);
  ASSERT_GT(run_ticks, 1000);
  long last = 0, steps = 0;
  for (const Told& step : told) {
    if (step.phase != "writing the outputs") {
      EXPECT_LT(step.ticks, 0) << step.phase << " writes no ticks";
      continue;
    }
    EXPECT_GE(step.ticks, last) << "the count went back";
    EXPECT_LE(step.ticks, run_ticks);
    last = step.ticks;
    ++steps;
  }
  EXPECT_GT(steps, 2);
  EXPECT_EQ(last, run_ticks) << "the last count is every tick of the run";
}

}  // namespace
}  // namespace pkm
