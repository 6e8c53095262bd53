// pkm servo as a library call on planned runs of the ch5 hexapod: the contour error tends to the plan's own
// path error as the current loop gets faster, a too small u_max is reported with its program lines, the
// coupled and decoupled plants agree where the coupling ratio is small and differ where it is not, and
// unstable gains are refused naming the drive, with nothing written.
#include "pipeline/servo_program.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/machine_file.hpp"
#include "pipeline/plan_program.hpp"
#include "report/csv_table.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {
namespace fs = std::filesystem;

fs::path servo_test_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("pkm_servo_program_{}_{}", name, ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// hexapod_ch5.yaml without its own servo: section, with `servo` (the section's text) instead.
Machine servo_test_machine(const fs::path& dir, const std::string& servo) {
  std::ifstream in(test::source_path("examples/machines/hexapod_ch5.yaml"));
  std::string text, line;
  bool skipping = false;
  while (std::getline(in, line)) {
    if (line.rfind("servo:", 0) == 0) {
      skipping = true;
      continue;
    }
    if (skipping && !line.empty() && line[0] != ' ' && line[0] != '#') skipping = false;
    if (!skipping) text += line + "\n";
  }
  const fs::path file = dir / "machine.yaml";
  std::ofstream(file) << text << servo;
  auto machine = load_machine_file(file.string());
  if (!machine) throw std::runtime_error(machine.error().message);
  return std::move(*machine);
}

std::string servo_section(double lag_ms, double loop_ms, double motor_kg_cm2, const std::string& extra = "",
                          double lead_mm = 10.0) {
  return fmt::format(
      "servo:\n  loop_period_ms: {}\n  drives:\n    current_time_constant_ms: {}\n    base_speed_mm_s: 500\n"
      "    base_force_N: 3000\n    motor_inertia_kg_cm2: {}\n    screw_lead_mm: {}\n{}",
      loop_ms, lag_ms, motor_kg_cm2, lead_mm, extra);
}

// The program planned into dir/plan.
pipeline::PlanProgramResult servo_test_plan(const Machine& machine, const fs::path& dir,
                                            const std::string& program, double rate_hz = 1000.0) {
  pipeline::PlanJob job;
  job.plan.rate_hz = rate_hz;
  job.program_path = test::source_path(program);
  job.out_directory = (dir / "plan").string();
  auto planned = pipeline::plan_program(machine, job);
  if (!planned) throw std::runtime_error(planned.error().message);
  return std::move(*planned);
}

Result<pipeline::ServoProgramResult> servo_test_run(const Machine& machine, const fs::path& dir,
                                                    bool coupled = true) {
  pipeline::ServoJob job;
  job.plan_directory = (dir / "plan").string();
  job.out_directory = (dir / (coupled ? "servo" : "servo_decoupled")).string();
  job.coupled = coupled;
  return pipeline::servo_program(machine, job);
}

// Two runs' following errors compared tick by tick over all drives: the largest difference, and the largest
// dynamic part of the first's, e − 4 T_μ q̇ (the P–P cascade's steady ramp error, the same on any plant,
// taken out), q̇ by central differences of the plan's set points.
std::pair<double, double> servo_test_difference(const fs::path& plan, const fs::path& a, const fs::path& b,
                                                double lag_s) {
  report::CsvReader setpoints, first, second;
  if (!setpoints.open((plan / "actuators.csv").string()).ok() ||
      !first.open((a / "servo.csv").string()).ok() || !second.open((b / "servo.csv").string()).ok())
    throw std::runtime_error("a run's file is missing");
  std::vector<std::vector<double>> q;
  std::vector<std::array<double, 6>> ec, ed;
  std::vector<double> row, x, y;
  while (setpoints.next(row)) q.push_back(row);
  while (first.next(x) && second.next(y)) {
    std::array<double, 6> c{}, d{};
    for (int j = 0; j < 6; ++j) {
      const int column = first.column(fmt::format("e{}_mm", j + 1));
      c[j] = x[column];
      d[j] = y[column];
    }
    ec.push_back(c);
    ed.push_back(d);
  }
  double difference = 0.0, dynamic = 0.0;
  const double h = q[1][0] - q[0][0];
  for (std::size_t k = 1; k + 1 < std::min(q.size(), ec.size()); ++k) {
    for (int j = 0; j < 6; ++j) {
      const double speed = (q[k + 1][j + 1] - q[k - 1][j + 1]) / (2.0 * h);
      difference = std::max(difference, std::abs(ec[k][j] - ed[k][j]));
      dynamic = std::max(dynamic, std::abs(ec[k][j] - 4.0 * lag_s * speed));
    }
  }
  return {difference, dynamic};
}

TEST(ServoProgram, ContourErrorTendsToThePlansPathErrorAsTheCurrentLoopGetsFaster) {
  const fs::path dir = servo_test_dir("limit");
  const Machine slow = servo_test_machine(dir, servo_section(1.0, 0.25, 1.5));
  // At 250 Hz the plan's own error (the drives' straight lines between set points against the curved
  // actuator law, at mid-period) is 3·10⁻⁵ mm, well above the 10⁻⁶ mm the run's files are written to.
  const auto planned = servo_test_plan(slow, dir, "examples/programs/ch5_line.ngc", 250.0);
  const double plan_error = planned.run.motion.max_path_error_mm;
  ASSERT_GT(plan_error, 2e-5);
  double previous = std::numeric_limits<double>::infinity();
  std::vector<double> errors;
  for (double lag_ms : {1.0, 0.1, 0.01}) {
    const Machine machine = servo_test_machine(dir, servo_section(lag_ms, lag_ms, 1.5));
    auto run = servo_test_run(machine, dir);
    ASSERT_TRUE(run.ok()) << run.error().message;
    const double error = run->summary.max_contour_error_mm;
    errors.push_back(error);
    EXPECT_LT(error, previous) << lag_ms;
    previous = error;
    // The following error of every drive shrinks with T_μ too (4 T_μ v on the line).
    for (int j = 0; j < 6; ++j)
      EXPECT_LT(run->summary.drive[j].max_following_error, 20.0 * lag_ms * 1e-3 * 60.0);
  }
  EXPECT_GT(errors.front(), 10.0 * plan_error);
  EXPECT_NEAR(errors.back(), plan_error, 0.1 * plan_error) << "plan " << plan_error;
  fs::remove_all(dir);
}

TEST(ServoProgram, ASmallCommandLimitIsReportedWithItsProgramLines) {
  const fs::path dir = servo_test_dir("clamps");
  const Machine generous = servo_test_machine(dir, servo_section(1.0, 0.25, 1.5, "    command_max: 5\n"));
  servo_test_plan(generous, dir, "examples/programs/ch5_line.ngc");
  auto fine = servo_test_run(generous, dir);
  ASSERT_TRUE(fine.ok()) << fine.error().message;
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(fine->summary.drive[j].command_clamps, 0) << j;
    EXPECT_LT(fine->summary.drive[j].peak_command, 5.0);
  }
  // A limit below the run's peak command: the drives are limited, on the lines with the accelerations.
  const double peak = fine->summary.drive[0].peak_command;
  const Machine tight = servo_test_machine(
      dir, servo_section(1.0, 0.25, 1.5, fmt::format("    command_max: {}\n", 0.5 * peak)));
  auto limited = servo_test_run(tight, dir);
  ASSERT_TRUE(limited.ok()) << limited.error().message;
  const servo::DriveServoSummary& d = limited->summary.drive[0];
  EXPECT_GT(d.command_clamps, 0);
  ASSERT_FALSE(d.clamp_lines.empty());
  for (int line : d.clamp_lines) EXPECT_TRUE(line == 5 || line == 6) << line;  // the G0 and the G1
  EXPECT_LE(d.peak_command, 0.5 * peak + 1e-9);
  EXPECT_GT(d.max_following_error, fine->summary.drive[0].max_following_error);
  const std::string summary_text = [&] {
    std::ifstream in(dir / "servo" / "servo_summary.json");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }();
  EXPECT_NE(summary_text.find("\"command_clamps\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(ServoProgram, CoupledAndDecoupledPlantsAgreeOnlyWhereTheCouplingIsSmall) {
  const fs::path dir = servo_test_dir("coupling");
  // Heavy motors behind a fine screw (ratio ≪ 0.3), light ones behind a coarse screw (ratio ≫ 0.3).
  for (const auto& [motor, lead] : {std::pair{40.0, 4.0}, std::pair{0.2, 20.0}}) {
    const Machine machine = servo_test_machine(dir, servo_section(1.0, 0.25, motor, "", lead));
    servo_test_plan(machine, dir, "examples/programs/pocket.ngc");
    auto coupled = servo_test_run(machine, dir, true);
    auto decoupled = servo_test_run(machine, dir, false);
    ASSERT_TRUE(coupled.ok()) << coupled.error().message;
    ASSERT_TRUE(decoupled.ok()) << decoupled.error().message;
    double ratio = 0.0;
    for (int j = 0; j < 6; ++j) ratio = std::max(ratio, coupled->summary.drive[j].max_coupling_ratio);
    const auto [difference, size] =
        servo_test_difference(dir / "plan", dir / "servo", dir / "servo_decoupled", 1e-3);
    SCOPED_TRACE(fmt::format("ratio {:.3f}, difference {:.3e} of {:.3e} mm", ratio, difference, size));
    if (motor > 1.0) {
      EXPECT_LT(ratio, 0.1);
      EXPECT_LT(difference, 0.05 * size);
      EXPECT_TRUE(coupled->summary.drive[0].coupled_lines.empty());
    } else {
      EXPECT_GT(ratio, 1.0);
      EXPECT_GT(difference, 0.15 * size);
      EXPECT_FALSE(coupled->summary.drive[0].coupled_lines.empty());
    }
  }
  fs::remove_all(dir);
}

TEST(ServoProgram, UnstableExplicitGainsAreRefusedNamingTheDriveAndNothingIsWritten) {
  const fs::path dir = servo_test_dir("unstable");
  const Machine stable = servo_test_machine(dir, servo_section(1.0, 0.25, 1.5));
  servo_test_plan(stable, dir, "examples/programs/ch5_line.ngc");
  // A position gain far above the speed loop's bandwidth.
  const std::string gains =
      "  tuning: explicit\n  drives:\n    current_time_constant_ms: 1.0\n    base_speed_mm_s: 500\n"
      "    base_force_N: 3000\n    motor_inertia_kg_cm2: 1.5\n    screw_lead_mm: 10\n"
      "    position_gain_per_s: 20000\n    speed_gain: 2\n";
  const Machine unstable = servo_test_machine(dir, "servo:\n  loop_period_ms: 0.25\n" + gains);
  auto run = servo_test_run(unstable, dir);
  ASSERT_FALSE(run.ok());
  EXPECT_NE(run.error().message.find("unstable"), std::string::npos) << run.error().message;
  EXPECT_NE(run.error().message.find("servo.drives["), std::string::npos) << run.error().message;
  EXPECT_NE(run.error().message.find("machine.yaml:"), std::string::npos) << run.error().message;
  EXPECT_FALSE(fs::exists(dir / "servo" / "servo.csv"));
  fs::remove_all(dir);
}

TEST(ServoProgram, TheTicksFileHoldsWhatTheSummarySays) {
  const fs::path dir = servo_test_dir("ticks");
  const Machine machine = servo_test_machine(dir, servo_section(1.0, 0.25, 1.5));
  const auto planned = servo_test_plan(machine, dir, "examples/programs/pocket.ngc");
  auto run = servo_test_run(machine, dir);
  ASSERT_TRUE(run.ok()) << run.error().message;
  report::CsvReader csv;
  ASSERT_TRUE(csv.open((dir / "servo" / "servo.csv").string()).ok());
  std::vector<double> row;
  std::array<double, 6> largest{};
  double contour = 0.0;
  long rows = 0;
  while (csv.next(row)) {
    ++rows;
    for (int j = 0; j < 6; ++j)
      largest[j] = std::max(largest[j], std::abs(row[csv.column(fmt::format("e{}_mm", j + 1))]));
    contour = std::max(contour, row[csv.column("contour_error_mm")]);
  }
  ASSERT_FALSE(csv.error().has_value());
  EXPECT_EQ(rows, run->summary.ticks);
  EXPECT_EQ(rows, planned.run.motion.ticks);
  for (int j = 0; j < 6; ++j)
    EXPECT_NEAR(largest[j], run->summary.drive[j].max_following_error, 1e-4 * largest[j] + 1e-12) << j;
  // The summary's maximum also counts the mid-periods.
  EXPECT_LE(contour, run->summary.max_contour_error_mm * (1.0 + 1e-4));
  EXPECT_GT(run->summary.max_lag_s, 0.0);
  EXPECT_EQ(run->json["kind"], "servo");
  EXPECT_TRUE(fs::exists(dir / "servo" / "servo_bode.csv"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pkm
