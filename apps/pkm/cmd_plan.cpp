// pkm plan PROGRAM --machine M.yaml [--rate HZ] [--override PCT] [--tolerance MM] [--law L --free F ...]
//   --out DIR [--json]:
// interprets a part program, plans it within the feed, path and actuator limits, and writes the servo-rate
// motion (ticks.h5, or actuators.csv and path.csv with --tables csv) and summary.json into DIR. With --law,
// the coordinates the operation leaves free are first chosen by that drive control law (as `pkm optimize`
// does) and the result is planned.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/units.hpp"
#include "number_options.hpp"
#include "pipeline/plan_program.hpp"
#include "planning/machine_warnings.hpp"
#include "planning/run_accuracy.hpp"
#include "program_options.hpp"
#include "progress_display.hpp"
#include "redundancy_options.hpp"
#include "statics/load_model.hpp"

namespace pkm::cli {

namespace {

// A blend tolerance beyond this is a typo (a tenth of a metre around every corner), not a wish.
constexpr double kMaxToleranceMm = 100.0;

struct PlanArguments {
  std::string program_path;
  std::string machine_path;
  std::string out_dir;
  std::string report_file;
  ProgramArguments program;
  RedundancyArguments redundancy;
  planning::PlanOptions options;
  double tolerance_mm = 0.0;
  const CLI::Option* tolerance_option = nullptr;
  bool json = false;
  bool no_path_error = false;
  bool dynamics = false;
  bool elastic = false;
  bool stiffness = false;
  formats::TickTables tables = formats::TickTables::hdf5;
};

void add_plan_options(CLI::App& cmd, PlanArguments& a) {
  cmd.add_option("program", a.program_path,
                 "part program: G-code, or CL data (told apart by content; --format)")
      ->required();
  cmd.add_option("--machine", a.machine_path, "machine file (YAML)")->required();
  cmd.add_option("--out", a.out_dir,
                 "directory for the servo-rate tables (ticks.h5, or CSV files: --tables) and summary.json")
      ->required();
  cmd.add_option("--rate", a.options.rate_hz, "servo rate, Hz")
      ->capture_default_str()
      ->check(number_in({1.0, 100000.0, true, true, "Hz"}));
  cmd.add_option("--override", a.options.override_pct, "operator feed override, % (> 0 and ≤ 200)")
      ->capture_default_str()
      ->check(number_in({0.0, 200.0, false, true, "%"}));
  a.tolerance_option =
      cmd.add_option("--tolerance", a.tolerance_mm,
                     "corner blending tolerance, mm (0: exact stop at corners; default: the machine file's)")
          ->check(number_in({0.0, kMaxToleranceMm, true, true, "mm"}));
  add_program_options(cmd, a.program);
  cmd.add_option("--max-ticks", a.options.max_ticks,
                 "refuse a motion of more servo ticks than this (the output grows with them)")
      ->capture_default_str()
      ->check(CLI::Range(1L, 1'000'000'000'000L));
  cmd.add_option("--max-samples", a.options.max_samples,
                 "refuse a path that needs more planning samples than this (the memory grows with them)")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{2}, std::size_t{1'000'000'000}));
  cmd.add_option("--lookahead-mm", a.options.lookahead_mm,
                 "the look-ahead window's path length, mm: the speeds are planned this far ahead at most")
      ->capture_default_str()
      ->check(number_in({0.0, 1e9, false, true, "mm"}));
  cmd.add_option("--lookahead-moves", a.options.lookahead_moves,
                 "the look-ahead window's moves: the speeds are planned this many moves ahead at most")
      ->capture_default_str()
      ->check(CLI::Range(1, 100'000'000));
  cmd.add_flag("--no-path-error", a.no_path_error,
               "skip the forward-kinematics check of the path error (faster)");
  auto* dynamics_flag = cmd.add_flag(
      "--dynamics", a.dynamics,
      "also the drive forces, power and energy (rigid bodies of the machine file's dynamics: section): "
      "the forces table and a dynamics block in summary.json");
  cmd.add_flag(
         "--elastic", a.elastic,
         "with --dynamics, also the elastic struts' response to the planned motion: the response table, "
         "the lowest natural frequency and the largest dynamic tool error")
      ->needs(dynamics_flag);
  cmd.add_flag("--stiffness", a.stiffness,
               "also the tool's deflection under --load with the struts as springs (the machine file's "
               "stiffness: section): the deflection table and a stiffness block in summary.json");
  cmd.add_flag("--json", a.json, "print the summary as JSON");
  cmd.add_option("--report", a.report_file, "also write the HTML report of the run to this file");
  cmd.add_option_function<std::string>(
         "--tables",
         [&a](const std::string& value) {
           a.tables = value == "hdf5" ? formats::TickTables::hdf5 : formats::TickTables::csv;
         },
         "the servo-rate tables as the groups of DIR/ticks.h5 (hdf5, default: compressed, for numpy and "
         "pandas through h5py) or as CSV files (csv: actuators.csv, path.csv, ...)")
      ->check(CLI::IsMember({"csv", "hdf5"}));
  add_redundancy_options(cmd, a.redundancy, false);
}

// The job the arguments describe (the law parsed already), the analyses and their load checked.
Result<pipeline::PlanJob> plan_job(const PlanArguments& a, std::optional<redundancy::OptimizeOptions> law) {
  pipeline::PlanJob job;
  job.law = std::move(law);
  job.program_path = a.program_path;
  job.program_options = a.program.options();
  job.plan = a.options;
  if (a.tolerance_option->count() > 0) job.plan.path_tolerance_mm = a.tolerance_mm;
  job.evaluate_path_error = !a.no_path_error;
  job.dynamics = a.dynamics;
  job.elastic = a.elastic;
  job.stiffness = a.stiffness;
  if (job.stiffness && a.redundancy.load.empty())
    return make_error(ErrorCode::bad_input, "--stiffness needs --load: the deflection is the load's");
  // --load is the law's process load; with --dynamics the drive forces carry it too, with --stiffness the
  // struts.
  if ((job.dynamics || job.stiffness) && !a.redundancy.load.empty()) {
    auto loads = statics::parse_load_spec(a.redundancy.load);
    Status lines = loads ? statics::check_load_lines(*loads, a.program_path) : Status(loads.error());
    if (!lines) return make_error(lines.error().code, "--load: " + lines.error().message);
    job.dynamics_load = std::move(*loads);
  }
  job.out_directory = a.out_dir;
  job.report_path = a.report_file;
  job.tick_tables = a.tables;
  return job;
}

// The analyses' lines of the table: drive forces and energy, the elastic response, the tool's deflection.
void print_plan_analyses(const analyses::PlanRun& run, bool angles) {
  if (run.dynamics) {
    const dynamics::RunDynamicsSummary& d = *run.dynamics;
    const std::string force_unit = angles ? "N·mm" : "N";
    int worst = 0;
    for (int j = 1; j < d.drives; ++j)
      if (d.peak_force_N[j] > d.peak_force_N[worst]) worst = j;
    std::cout << fmt::format(
        "  drive force       max {:.1f} {} (drive {}, line {})   power max {:.1f} W (line {})\n",
        d.peak_force_N[worst], force_unit, worst + 1, d.peak_force_line[worst], d.peak_total_power_W,
        d.peak_total_power_line);
    std::cout << fmt::format(
        "  drive energy      {:.3f} J no recovery, {:.3f} J braking free, {:.3f} J with recovery\n",
        d.energy.no_recovery_J, d.energy.braking_free_J, d.energy.recovery_J);
  }
  if (run.elastic) {
    const dynamics::ElasticRunSummary& e = *run.elastic;
    std::cout << fmt::format("  elastic response  lowest natural frequency {:.2f} Hz at the start\n",
                             e.lowest_frequency_Hz);
    std::cout << fmt::format(
        "  dynamic error     max {:.3f} µm at the tool (line {}; static sag {:.3f} µm)\n",
        e.max_tool_error_mm * 1e3, e.max_tool_error_line, e.start_deflection_mm * 1e3);
  }
  if (run.deflection) {
    const stiffness::DeflectionSummary& f = *run.deflection;
    std::cout << fmt::format(
        "  tool deflection   max {:.3f} µm along the tool axis (line {}), rms {:.3f} µm; max {:.3f} µm "
        "(line {})\n",
        f.max_normal_mm * 1e3, f.max_normal_line, f.rms_normal_mm * 1e3, f.max_deflection_mm * 1e3,
        f.max_deflection_line);
  }
}

void print_plan_table(const pipeline::PlanProgramResult& result, const Machine& machine,
                      const PlanArguments& a, const pipeline::PlanJob& job) {
  const planning::RunSummary& run = result.run.motion;
  const bool angles = machine.mechanism->actuators_are_angles();
  const std::string unit = angles ? "deg" : "mm";
  const double scale = angles ? deg_from_rad(1.0) : 1.0;
  std::cout << fmt::format("{}: {} blocks on {} ({}), {} ticks at {} Hz\n", a.program_path,
                           result.statistics.blocks, machine.name, a.machine_path, run.ticks, run.rate_hz);
  std::cout << fmt::format("  duration          {:.3f} s (path {:.1f} mm, override {} %)\n", run.duration_s,
                           result.statistics.length_mm, job.plan.override_pct);
  std::cout << fmt::format("  actuator speed    max {:.3f} {}/s   accel max {:.3f} {}/s²\n",
                           run.max_actuator_speed * scale, unit, run.max_actuator_accel * scale, unit);
  std::cout << fmt::format("  path speed        max {:.3f} mm/s ({:.1f} % of the programmed feed at most)\n",
                           run.max_path_speed, 100.0 * run.max_feed_ratio);
  if (job.evaluate_path_error) {
    std::cout << fmt::format(
        "  path error        max {:.3g} mm at line {} (FK of the actuators at mid-period; bound {:g} mm)\n",
        run.max_path_error_mm, run.max_path_error_line, result.path_error_bound_mm);
  }
  if (result.law) {
    std::cout << fmt::format("  {} law           Σ max|ΔL| {:.3f} mm (held constant: {:.3f} mm), free {}\n",
                             a.redundancy.law, result.law->chosen().metrics.increment_sum_mm,
                             result.law->constant.increment_sum_mm, a.redundancy.free);
  }
  print_plan_analyses(result.run, angles);
  if (a.tables == formats::TickTables::hdf5) {
    std::cout << fmt::format("  written           {}/ticks.h5 (actuators, path{}{}{}), summary.json\n",
                             a.out_dir, result.run.dynamics ? ", forces" : "",
                             result.run.elastic ? ", response" : "",
                             result.run.deflection ? ", deflection" : "");
    return;
  }
  std::cout << fmt::format("  written           {}/actuators.csv, path.csv, summary.json{}{}{}\n", a.out_dir,
                           result.run.dynamics ? ", forces.csv" : "",
                           result.run.elastic ? ", response.csv" : "",
                           result.run.deflection ? ", deflection.csv" : "");
}

int run_plan(const PlanArguments& a) {
  std::optional<redundancy::OptimizeOptions> law;
  if (!a.redundancy.law.empty()) {
    auto parsed = redundancy_options(a.redundancy);
    if (!parsed) return report_error("plan", parsed.error());
    law = std::move(*parsed);
  }
  auto machine = load_machine_or_report(a.machine_path);
  if (!machine) return report_error("plan", machine.error());
  auto job = plan_job(a, std::move(law));
  if (!job) return report_error("plan", job.error());
  for (const std::string& warning : planning::machine_warnings(*machine))
    std::cerr << "pkm plan: warning: " << warning << "\n";
  ProgressDisplay progress("plan", "reading the program");
  job->progress = progress.sink();
  auto result = pipeline::plan_program(*machine, *job);
  progress.finish();
  if (!result) return report_error("plan", result.error(), a.json);
  for (const std::string& note : result->program_notes) std::cerr << "pkm plan: note: " << note << "\n";
  if (a.json) {
    nlohmann::json summary = result->summary;
    summary["planning_time_s"] = result->planning_s;
    if (job->law) summary["redundancy"] = result->law_summary;
    print_json(summary);
    return 0;
  }
  print_plan_table(*result, *machine, a, *job);
  return 0;
}

}  // namespace

void add_plan_command(CLI::App& app, int& exit_code) {
  auto* cmd =
      app.add_subcommand("plan", "plan a part program on a machine: actuator motion at the servo rate");
  auto arguments = std::make_shared<PlanArguments>();
  add_plan_options(*cmd, *arguments);
  cmd->callback([arguments, &exit_code] { exit_code = run_plan(*arguments); });
}

}  // namespace pkm::cli
