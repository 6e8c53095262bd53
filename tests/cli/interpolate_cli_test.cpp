// pkm interpolate from the command line: steps.csv, steps.bin and summary.json agree with each other and with
// the printed summary; bad input exits 2 naming the option or the program line, and leaves no files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "cli/cli_support.hpp"
#include "interpolation/drive_output/step_stream.hpp"
#include "interpolation/drive_output/steps_csv.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string fresh_interpolate_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_interpolate_cli_" + name);
  fs::remove_all(dir);
  return dir.string();
}

std::string ch5_command(const std::string& program, const std::string& options, const std::string& out) {
  return "interpolate " + test::source_path(program) + " --machine " +
         test::source_path("examples/machines/hexapod_ch5.yaml") + " " + options + " --out " + out;
}

TEST(InterpolateCli, WritesStepsInBothFormatsAndTheSummary) {
  const std::string out = fresh_interpolate_dir("line");
  const auto run = test::run_pkm(
      ch5_command("examples/programs/ch5_line.ngc",
                  "--period-ms 2 --step-mm 0.001 --method carrier-corrected --rho-max 0.001 --json", out),
      false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  for (const char* key : {"max_contour_error_mm", "rms_contour_error_mm", "start_error_mm", "periods",
                          "fk_solves_per_period", "max_compute_us_per_period"}) {
    EXPECT_TRUE(summary.contains(key)) << key;
  }
  EXPECT_EQ(summary["method"], "carrier-corrected");
  EXPECT_DOUBLE_EQ(summary["fk_solves_per_period"].get<double>(), 1.0);
  EXPECT_LE(summary["max_contour_error_after_first_period_mm"].get<double>(), 1e-3);
  std::ifstream file(fs::path(out) / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(file)["periods"], summary["periods"]);

  auto csv = interpolation::read_steps_csv((fs::path(out) / "steps.csv").string());
  ASSERT_TRUE(csv.ok()) << csv.error().message;
  ASSERT_EQ(static_cast<long>(csv->periods.size()), summary["periods"].get<long>());
  interpolation::StepStreamReader binary;
  ASSERT_TRUE(binary.open((fs::path(out) / "steps.bin").string()).ok());
  interpolation::StepPeriod period;
  std::size_t index = 0;
  while (binary.next(period)) {
    ASSERT_LT(index, csv->periods.size());
    for (int j = 0; j < 6; ++j) {
      ASSERT_EQ(period.steps[j], csv->periods[index].steps[j]);
      ASSERT_EQ(period.position[j], csv->periods[index].position[j]);
    }
    ++index;
  }
  EXPECT_EQ(index, csv->periods.size());
  // The last position codes are the summary's end positions.
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(csv->periods.back().position[j], summary["actuators"][j]["end_position_steps"].get<long>());
  }
}

TEST(InterpolateCli, EveryMethodRunsAndTheCorrectionBeatsTheNaiveRegisters) {
  // 25 mm of the ch5 test line's direction from the home point: the estimating method takes a tact per step,
  // which under the sanitizers is slow on the whole 100 mm line.
  const std::string program =
      test::write_temp_file("interpolate_methods.ngc", "G21 G90 G17 G94\nG1 X25 Y0 Z0 F3000\nM2\n");
  std::map<std::string, double> error;
  for (const char* method : {"exact", "carrier", "carrier-corrected", "estimating"}) {
    const std::string out = fresh_interpolate_dir(method);
    const auto run = test::run_pkm(
        "interpolate " + program + " --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") +
            " --period-ms 1 --step-mm 0.001 --json --method " + method + " --out " + out,
        false);
    ASSERT_EQ(run.exit_code, 0) << method << run.out;
    const auto summary = nlohmann::json::parse(run.out);
    error[method] = summary["max_contour_error_mm"].get<double>();
    EXPECT_TRUE(fs::exists(fs::path(out) / "steps.bin")) << method;
  }
  EXPECT_LT(2.0 * error["carrier-corrected"], error["carrier"]);
  // Each tact stays within δ = ρ_max of the line; between tacts the drives move on, so a little more.
  EXPECT_LT(error["estimating"], 1.2e-3);
  EXPECT_LT(error["estimating"], error["carrier"]);
}

TEST(InterpolateCli, BadOptionsExitWithTwoAndWriteNothing) {
  const std::string out = fresh_interpolate_dir("bad");
  for (const auto& [options, word] : std::vector<std::pair<std::string, std::string>>{
           {"--period-ms 50", "--period-ms"},
           {"--method fastest", "--method"},
           {"--step-mm 0", "--step-mm"},
           {"--override-at 1:300", "--override-at"},
           {"--accel cubic", "--accel"},
           {"--method estimating --candidates 9", "--candidates"}}) {
    const auto run = test::run_pkm(ch5_command("examples/programs/ch5_line.ngc", options, out));
    EXPECT_EQ(run.exit_code, 2) << options << run.out;
    EXPECT_NE(run.out.find(word), std::string::npos) << run.out;
  }
  const std::string program = test::write_temp_file("interpolate_bad.ngc", "G1 X1 F100\nG2 X5\n");
  const auto run = test::run_pkm("interpolate " + program + " --machine " +
                                 test::source_path("examples/machines/hexapod_ch5.yaml") + " --out " + out);
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("interpolate_bad.ngc:2"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(fs::path(out) / "steps.csv"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "steps.bin"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "summary.json"));
}

TEST(InterpolateCli, DriveOptionsDefaultToTheMachineFilesDrivesSection) {
  std::ifstream in(test::source_path("examples/machines/hexapod_ch5.yaml"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string shipped = "drives: {step_mm: 0.001, max_step_rate_hz: 200000, period_ms: 1}";
  const auto at = text.find(shipped);
  ASSERT_NE(at, std::string::npos) << "the ch5 example's drives: line changed";
  // 20 kHz at 2 ms is at most 40 steps per period; the test line at 50 mm/s asks up to 50 of 0.002 mm.
  text.replace(at, shipped.size(), "drives: {step_mm: 0.002, max_step_rate_hz: 20000, period_ms: 2}");
  const std::string machine = test::write_temp_file("drives_hexapod.yaml", text);
  const std::string program = test::source_path("examples/programs/ch5_line.ngc");
  const std::string out = fresh_interpolate_dir("drives");

  const auto from_file =
      test::run_pkm("interpolate " + program + " --machine " + machine + " --json --out " + out, false);
  ASSERT_EQ(from_file.exit_code, 0) << from_file.out;
  const auto summary = nlohmann::json::parse(from_file.out);
  EXPECT_DOUBLE_EQ(summary["period_ms"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(summary["step_mm"].get<double>(), 0.002);
  EXPECT_LE(summary["max_steps_per_period"].get<int>(), 40);
  EXPECT_GT(summary["real_time_s"].get<double>(), summary["ideal_time_s"].get<double>());

  // The command line wins over the file.
  const auto given =
      test::run_pkm("interpolate " + program + " --machine " + machine +
                        " --period-ms 1 --step-mm 0.001 --max-step-rate 1e6 --json --out " + out,
                    false);
  ASSERT_EQ(given.exit_code, 0) << given.out;
  const auto overridden = nlohmann::json::parse(given.out);
  EXPECT_DOUBLE_EQ(overridden["period_ms"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(overridden["step_mm"].get<double>(), 0.001);
  EXPECT_GT(overridden["max_steps_per_period"].get<int>(), 40);
}

TEST(InterpolateCli, AStalledOverrideFailsWithoutHalfWrittenFiles) {
  const std::string out = fresh_interpolate_dir("stalled");
  const auto run = test::run_pkm(ch5_command("examples/programs/ch5_line.ngc", "--override-at 0.5:0", out));
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("never end"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(fs::path(out) / "steps.csv"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "steps.bin"));
  // No staged temporaries either.
  if (fs::exists(out)) {
    EXPECT_TRUE(fs::is_empty(out));
  }
}

}  // namespace
}  // namespace pkm
