// pkm interpolate PROGRAM --machine M.yaml --period-ms H --step-mm D
//   --method exact|carrier|carrier-corrected|estimating [--rho-max MM] --out DIR [--json]:
// plans the part program (as pkm plan), then turns the planned motion into whole drive steps per servo period
// (Smirnov 2019): DIR/steps.csv and DIR/steps.bin (per period and actuator: signed steps and position code),
// DIR/contour.csv (per period: the contour error and where the tool is) and DIR/summary.json with the contour
// error the drives would produce; --report FILE adds the HTML report. Nothing is left in DIR if the run
// fails.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <limits>

#include "cli_common.hpp"
#include "commands.hpp"
#include "number_options.hpp"
#include "pipeline/interpolate_program.hpp"
#include "program_options.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

namespace {

struct InterpolateArguments {
  std::string program;
  std::string machine;
  std::string out;
  std::string method = "carrier-corrected";
  ProgramArguments program_options;
  double period_ms = 1.0;
  double step_mm = 0.001;
  double rho_max_mm = 1e-3;
  double delta_rho_max = 0.0;
  double override_pct = 100.0;
  std::string override_at;
  std::string accel = "s-curve";
  double max_step_rate_hz = 0.0;
  int error_samples = 5;
  double deviation_mm = 0.0;
  std::string candidates = "all-six";
  bool no_chord_check = false;
  bool orientation = false;
  bool no_linearise = false;
  bool json = false;
  std::string report;
  // Which of the drive options were given: the others come from the machine file's `drives:`.
  bool period_given = false;
  bool step_given = false;
  bool step_rate_given = false;
};

/// The job from the command line: the method's options as given; drive parameters left out come from the
/// machine file in the library (pipeline/interpolate_program.hpp).
Result<pipeline::InterpolateJob> interpolate_job(const InterpolateArguments& args, const Machine& machine) {
  pipeline::InterpolateJob job;
  interpolation::InterpolateOptions& options = job.options;
  auto method = interpolation::method_from_string(args.method);
  if (!method) {
    return Error{
        ErrorCode::bad_input,
        fmt::format("--method '{}': expected exact, carrier, carrier-corrected or estimating", args.method)};
  }
  options.method = *method;
  if (args.period_given) job.period_ms = args.period_ms;
  if (args.step_given) {
    if (!(args.step_mm > 0.0)) {
      return Error{
          ErrorCode::bad_input,
          fmt::format("--step-mm {} must be a positive drive resolution (mm per step)", args.step_mm)};
    }
    job.step = args.step_mm;
  }
  if (args.step_rate_given) job.max_step_rate_hz = args.max_step_rate_hz;
  options.rho_max_mm = args.rho_max_mm;
  if (args.delta_rho_max > 0.0) options.delta_rho_max = args.delta_rho_max;
  options.chord_check = !args.no_chord_check;
  options.orientation_criterion = args.orientation;
  options.linearise = !args.no_linearise;
  if (args.error_samples < 1) return Error{ErrorCode::bad_input, "--error-samples must be at least 1"};
  options.error_samples = args.error_samples;
  if (args.accel != "linear" && args.accel != "s-curve") {
    return Error{ErrorCode::bad_input, fmt::format("--accel '{}': expected linear or s-curve", args.accel)};
  }
  job.accel = args.accel == "linear" ? interpolation::RampShape::linear : interpolation::RampShape::s_curve;
  job.override_pct = args.override_pct;
  auto changes = interpolation::parse_override_changes(args.override_at);
  if (!changes) return Error{changes.error().code, "--override-at: " + changes.error().message};
  job.override_changes = *changes;
  options.estimating.deviation_mm = args.deviation_mm > 0.0 ? args.deviation_mm : args.rho_max_mm;
  if (args.candidates == "all-six" || args.candidates == "all") {
    options.estimating.candidates = interpolation::CandidateSet::all_six;
  } else if (args.candidates == "one-to-all") {
    options.estimating.candidates = interpolation::CandidateSet::one_to_all;
  } else {
    int k = 0;
    try {
      std::size_t used = 0;
      k = std::stoi(args.candidates, &used);
      if (used != args.candidates.size()) k = 0;
    } catch (const std::exception&) {
      k = 0;
    }
    if (k < 1 || k > machine.mechanism->actuator_count()) {
      return Error{ErrorCode::bad_input,
                   fmt::format("--candidates '{}': expected all-six, one-to-all or a number of struts 1…{}",
                               args.candidates, machine.mechanism->actuator_count())};
    }
    options.estimating.candidates = interpolation::CandidateSet::exactly_k;
    options.estimating.struts_per_tact = k;
  }
  job.program_path = args.program;
  job.program_options = args.program_options.options();
  job.out_directory = args.out;
  job.report_path = args.report;
  return job;
}

void print_interpolation_table(const interpolation::InterpolateSummary& s, const std::string& program,
                               const std::string& out) {
  const interpolation::ContourStatistics& c = s.contour;
  std::cout << fmt::format("{}: {} method, {} periods of {} ms, step {}\n", program, to_string(s.method),
                           s.periods, s.period_s * 1e3, s.step_mm);
  std::cout << fmt::format(
      "  time              real {:.4f} s, ideal {:.4f} s ({} periods slowed by the chord check)\n",
      s.real_time_s, s.ideal_time_s, s.carrier.chord_reduced_periods);
  std::cout << fmt::format(
      "  contour error     max {:.3g} mm (line {}), rms {:.3g} mm, after the first period {:.3g} mm\n",
      c.max_error_mm, c.max_error_line, c.rms_error_mm, c.max_error_after_first_mm);
  std::cout << fmt::format("  start / end       {:.3g} mm / {:.3g} mm (ρ_max {} mm, δρ_max {:.3f})\n",
                           c.start_error_mm, c.end_error_mm, s.rho_max_mm, s.delta_rho_max);
  std::cout << fmt::format(
      "  per period        {:.1f} FK solves, compute max {:.2f} µs, mean {:.2f} µs, max {} steps\n",
      s.fk_solves_per_period, s.max_compute_us_per_period, s.mean_compute_us_per_period,
      s.max_steps_per_period);
  const DurationDistribution& t = s.period_time;
  std::cout << fmt::format(
      "  period time       p50 {:.2f} µs, p99 {:.2f} µs, p99.9 {:.2f} µs, max {:.1f} µs of {} periods "
      "({} above 10 µs; compute only)\n",
      t.p50_us, t.p99_us, t.p99_9_us, t.max_us, t.count, t.over_budget);
  std::cout << fmt::format("  written           {}/steps.csv, steps.bin, contour.csv, summary.json\n", out);
}

}  // namespace

void add_interpolate_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "interpolate", "turn a part program into whole drive steps per servo period (Smirnov 2019 ch. 5)");
  auto args = std::make_shared<InterpolateArguments>();
  cmd->add_option("program", args->program,
                  "part program: G-code, or CL data (told apart by content; --format)")
      ->required();
  cmd->add_option("--machine", args->machine, "machine file (YAML)")->required();
  cmd->add_option("--out", args->out, "directory for steps.csv, steps.bin, contour.csv and summary.json")
      ->required();
  auto* period_option =
      cmd->add_option("--period-ms", args->period_ms,
                      "servo (carrier) period h, ms (0.1…20; default drives.period_ms, else 1)")
          ->check(number_in({0.1, 20.0, true, true, "ms"}));
  auto* step_option = cmd->add_option("--step-mm", args->step_mm,
                                      "drive resolution Δ, mm per step (deg for angular actuators; default "
                                      "drives.step_mm, else 0.001)")
                          ->check(number_in({0.0, 10.0, false, true, "mm"}));
  cmd->add_option("--method", args->method, "exact, carrier, carrier-corrected or estimating")
      ->capture_default_str();
  cmd->add_option("--rho-max", args->rho_max_mm, "contour tolerance ρ_max, mm")
      ->capture_default_str()
      ->check(number_in({interpolation::kMinContourToleranceMm, 100.0, true, true, "mm"}));
  cmd->add_option("--delta-rho-max", args->delta_rho_max,
                  "error amplification δρ_max (default: the largest along the path)")
      ->check(number_in({0.0, 1e6, true, true, ""}));
  cmd->add_option("--override", args->override_pct, "operator feed override at the start, % (> 0 and ≤ 200)")
      ->capture_default_str()
      ->check(number_in({0.0, 200.0, false, true, "%"}));
  cmd->add_option("--override-at", args->override_at,
                  "override changes during the run, TIME_S:PERCENT,… (take effect from period i+2)");
  cmd->add_option("--accel", args->accel, "acceleration law: linear or s-curve")->capture_default_str();
  auto* step_rate_option =
      cmd->add_option("--max-step-rate", args->max_step_rate_hz,
                      "largest step rate of a drive, Hz (default drives.max_step_rate_hz)")
          ->check(number_in({0.0, 1e9, true, true, "Hz"}));
  cmd->add_option("--error-samples", args->error_samples, "contour-error points inside each period")
      ->capture_default_str()
      ->check(number_in({1.0, 1000.0, true, true, "", true}));
  cmd->add_option("--deviation-mm", args->deviation_mm, "estimating: allowed deviation δ (default ρ_max)")
      ->check(number_in({0.0, 100.0, true, true, "mm"}));
  cmd->add_option("--candidates", args->candidates, "estimating: all-six, one-to-all or struts per tact")
      ->capture_default_str();
  add_program_options(*cmd, args->program_options);
  cmd->add_flag("--no-chord-check", args->no_chord_check, "do not slow down for the chord error (eq. 155)");
  cmd->add_flag("--orientation", args->orientation,
                "carrier-corrected/estimating: keep the angles nearest the programmed ones (eq. 143)");
  cmd->add_flag("--no-linearise", args->no_linearise,
                "carrier-corrected: forward kinematics for every combination (the reference)");
  cmd->add_flag("--json", args->json, "print the summary as JSON");
  cmd->add_option("--report", args->report, "also write the HTML report of the run to this file");
  cmd->callback([args, period_option, step_option, step_rate_option, &exit_code] {
    auto machine = load_machine_or_report(args->machine);
    if (!machine) {
      exit_code = report_error("interpolate", machine.error());
      return;
    }
    args->period_given = period_option->count() > 0;
    args->step_given = step_option->count() > 0;
    args->step_rate_given = step_rate_option->count() > 0;
    auto job = interpolate_job(*args, *machine);
    if (!job) {
      exit_code = report_error("interpolate", job.error());
      return;
    }
    ProgressDisplay progress("interpolate", "reading the program");
    job->progress = progress.sink();
    auto result = pipeline::interpolate_program(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("interpolate", result.error());
      return;
    }
    if (args->json) {
      print_json(result->json);
      return;
    }
    print_interpolation_table(result->summary, args->program, args->out);
  });
}

}  // namespace pkm::cli
