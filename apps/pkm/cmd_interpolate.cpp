// pkm interpolate PROGRAM --machine M.yaml --period-ms H --step-mm D
//   --method exact|carrier|carrier-corrected|estimating [--rho-max MM] --out DIR [--json]:
// plans the part program (as pkm plan), then turns the planned motion into whole drive steps per servo period
// (spec ch5): DIR/steps.csv and DIR/steps.bin (per period and actuator: signed steps and position code),
// DIR/contour.csv (per period: the contour error and where the tool is) and DIR/summary.json with the contour
// error the drives would produce; --report FILE adds the HTML report. Nothing is left in DIR if the run
// fails.
#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <limits>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/output_set.hpp"
#include "core/units.hpp"
#include "interpolation/contour_trace.hpp"
#include "interpolation/interpolate_run.hpp"
#include "interpolation/step_stream.hpp"
#include "interpolation/steps_csv.hpp"
#include "number_options.hpp"
#include "planning/motion_plan.hpp"
#include "program/part_program.hpp"
#include "report/report_data.hpp"

namespace pkm::cli {

namespace {

struct InterpolateArguments {
  std::string program;
  std::string machine;
  std::string out;
  std::string method = "carrier-corrected";
  std::string tool_table;
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

/// Fills the options the command line left out from the machine file's `drives:` section.
void take_drive_defaults(InterpolateArguments& args, const Machine& machine) {
  if (!args.period_given && machine.drives.period_ms) args.period_ms = *machine.drives.period_ms;
  if (!args.step_given && machine.drives.step) args.step_mm = *machine.drives.step;
  if (!args.step_rate_given && machine.drives.max_step_rate_hz)
    args.max_step_rate_hz = *machine.drives.max_step_rate_hz;
}

Result<interpolation::InterpolateOptions> interpolate_options(const InterpolateArguments& args,
                                                              const Machine& machine) {
  interpolation::InterpolateOptions options;
  auto method = interpolation::method_from_string(args.method);
  if (!method) {
    return Error{
        ErrorCode::bad_input,
        fmt::format("--method '{}': expected exact, carrier, carrier-corrected or estimating", args.method)};
  }
  options.method = *method;
  options.period_s = args.period_ms * 1e-3;
  if (!(args.step_mm > 0.0)) {
    return Error{ErrorCode::bad_input,
                 fmt::format("--step-mm {} must be a positive drive resolution (mm per step)", args.step_mm)};
  }
  options.step_mm = args.step_mm;
  options.rho_max_mm = args.rho_max_mm;
  if (args.delta_rho_max > 0.0) options.delta_rho_max = args.delta_rho_max;
  options.chord_check = !args.no_chord_check;
  options.orientation_criterion = args.orientation;
  options.linearise = !args.no_linearise;
  if (args.error_samples < 1) return Error{ErrorCode::bad_input, "--error-samples must be at least 1"};
  options.error_samples = args.error_samples;
  if (args.max_step_rate_hz > 0.0) options.max_step_rate_hz = args.max_step_rate_hz;
  if (args.accel != "linear" && args.accel != "s-curve") {
    return Error{ErrorCode::bad_input, fmt::format("--accel '{}': expected linear or s-curve", args.accel)};
  }
  // Online changes are percentages of the programmed feed; the plan already runs at --override.
  auto changes = interpolation::parse_override_changes(args.override_at);
  if (!changes) return changes.error();
  for (auto& change : *changes) change.percent *= 100.0 / args.override_pct;
  options.feed_override.changes = *changes;
  options.feed_override.shape =
      args.accel == "linear" ? interpolation::RampShape::linear : interpolation::RampShape::s_curve;
  options.feed_override.full_ramp_s =
      (machine.motion.max_feed_mm_min / 60.0) / machine.motion.path_accel_mm_s2;
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
  return options;
}

void print_interpolation_table(const nlohmann::json& s, const std::string& program, const std::string& out) {
  std::cout << fmt::format("{}: {} method, {} periods of {} ms, step {}\n", program,
                           s["method"].get<std::string>(), s["periods"].get<long>(),
                           s["period_ms"].get<double>(),
                           s.contains("step_mm") ? s["step_mm"].get<double>() : s["step_deg"].get<double>());
  std::cout << fmt::format(
      "  time              real {:.4f} s, ideal {:.4f} s ({} periods slowed by the chord check)\n",
      s["real_time_s"].get<double>(), s["ideal_time_s"].get<double>(),
      s["chord_reduced_periods"].get<long>());
  std::cout << fmt::format(
      "  contour error     max {:.3g} mm (line {}), rms {:.3g} mm, after the first period {:.3g} mm\n",
      s["max_contour_error_mm"].get<double>(), s["max_contour_error_line"].get<int>(),
      s["rms_contour_error_mm"].get<double>(), s["max_contour_error_after_first_period_mm"].get<double>());
  std::cout << fmt::format("  start / end       {:.3g} mm / {:.3g} mm (ρ_max {} mm, δρ_max {:.3f})\n",
                           s["start_error_mm"].get<double>(), s["end_error_mm"].get<double>(),
                           s["rho_max_mm"].get<double>(), s["delta_rho_max"].get<double>());
  std::cout << fmt::format(
      "  per period        {:.1f} FK solves, compute max {:.2f} µs, mean {:.2f} µs, max {} steps\n",
      s["fk_solves_per_period"].get<double>(), s["max_compute_us_per_period"].get<double>(),
      s["mean_compute_us_per_period"].get<double>(), s["max_steps_per_period"].get<int>());
  std::cout << fmt::format(
      "  period time       p50 {:.2f} µs, p99 {:.2f} µs, p99.9 {:.2f} µs, max {:.1f} µs of {} periods "
      "({} above 10 µs; compute only)\n",
      s["period_time_us_p50"].get<double>(), s["period_time_us_p99"].get<double>(),
      s["period_time_us_p99_9"].get<double>(), s["period_time_us_max"].get<double>(),
      s["period_time_count"].get<long>(), s["period_time_over_10us"].get<long>());
  std::cout << fmt::format("  written           {}/steps.csv, steps.bin, contour.csv, summary.json\n", out);
}

}  // namespace

void add_interpolate_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "interpolate", "turn a part program into whole drive steps per servo period (ch5 interpolation)");
  auto args = std::make_shared<InterpolateArguments>();
  cmd->add_option("program", args->program, "part program: G-code, or APT CL data (.cl, .cls, .apt)")
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
      ->check(number_in({0.0, 100.0, false, true, "mm"}));
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
  cmd->add_option("--tool-table", args->tool_table, "LinuxCNC tool table for G43");
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
    take_drive_defaults(*args, *machine);
    auto options = interpolate_options(*args, *machine);
    if (!options) {
      exit_code = report_error("interpolate", options.error());
      return;
    }
    if (args->accel == "linear") {
      // No jerk limit: the plan's moving-average filter shrinks to one period (trapezoidal speed).
      machine->motion.path_jerk_mm_s3 = std::numeric_limits<double>::max();
    }
    const planning::ProgramStart start = planning::program_start(*machine);
    program::InterpretOptions interpret;
    interpret.start_mm = start.start_mm;
    interpret.start_abc_deg = start.start_abc_deg;
    interpret.tool_table_path = args->tool_table;
    auto program = program::load_part_program(args->program, interpret);
    if (!program) {
      exit_code = report_error("interpolate", program.error());
      return;
    }
    planning::PlanOptions plan_options;
    plan_options.rate_hz = 1.0 / options->period_s;
    plan_options.override_pct = args->override_pct;
    if (!(options->period_s >= 1e-4 - 1e-12 && options->period_s <= 2e-2 + 1e-12)) {
      exit_code = report_error(
          "interpolate",
          Error{ErrorCode::bad_input, fmt::format("--period-ms {} is outside 0.1…20 ms", args->period_ms)});
      return;
    }
    auto plan = planning::plan_motion(*machine, *program, plan_options);
    if (!plan) {
      exit_code = report_error("interpolate", plan.error());
      return;
    }
    auto timing = interpolation::IdealTiming::from_plan(*plan, *machine);
    if (!timing) {
      exit_code = report_error("interpolate", timing.error());
      return;
    }
    // The step files, the contour trace, the summary and the report replace the previous run's together.
    OutputSet outputs;
    if (Status used = outputs.use_directory(args->out); !used) {
      exit_code = report_error("interpolate", used.error());
      return;
    }
    interpolation::StepStreamHeader header;
    header.actuators = machine->mechanism->actuator_count();
    header.period_s = options->period_s;
    // The stream's step is in the actuators' own unit: mm, or rad for angular actuators (given in deg).
    header.step_mm =
        machine->mechanism->actuators_are_angles() ? options->step_mm * (kPi / 180.0) : options->step_mm;
    header.machine = machine->source;
    interpolation::StepsCsvWriter csv;
    interpolation::StepStreamWriter binary;
    if (isatty(STDERR_FILENO) && plan->duration_s / options->period_s > 200000)
      options->progress = draw_progress;
    auto start_steps = interpolation::start_positions(*machine, plan->path, options->step_mm);
    if (!start_steps) {
      exit_code = report_error("interpolate", start_steps.error());
      return;
    }
    header.start_position = *start_steps;
    auto opened_csv = csv.open(outputs.staged_path("steps.csv"), header);
    if (!opened_csv) {
      exit_code = report_error("interpolate", opened_csv.error());
      return;
    }
    auto opened_bin = binary.open(outputs.staged_path("steps.bin"), header);
    if (!opened_bin) {
      exit_code = report_error("interpolate", opened_bin.error());
      return;
    }
    interpolation::ContourTraceWriter trace;
    if (auto opened_trace = trace.open(outputs.staged_path("contour.csv")); !opened_trace) {
      exit_code = report_error("interpolate", opened_trace.error());
      return;
    }
    Status trace_status = ok_status();
    options->on_period = [&](const interpolation::StepPeriod& period,
                             const interpolation::PeriodContour& contour, const Eigen::Vector3d& path_mm) {
      if (trace_status) trace_status = trace.add(period, contour, path_mm);
    };
    auto summary =
        interpolation::interpolate(*machine, plan->path, *timing, *options, {&csv, &binary}, program->source);
    if (!summary) {
      exit_code = report_error("interpolate", summary.error());
      return;
    }
    if (trace_status) trace_status = trace.finish();
    if (!trace_status) {
      exit_code = report_error("interpolate", trace_status.error());
      return;
    }
    nlohmann::json json = interpolation::interpolation_summary_json(*summary, *machine);
    json["program"] = program->source;
    json["blocks"] = plan->statistics.blocks;
    json["override_pct"] = args->override_pct;
    json["accel"] = args->accel;
    if (options->max_step_rate_hz) json["max_step_rate_hz"] = *options->max_step_rate_hz;
    if (Status written = write_file_atomically(outputs.staged_path("summary.json"), json.dump(2) + "\n");
        !written) {
      exit_code = report_error("interpolate", written.error());
      return;
    }
    if (Status written = stage_directory_report(outputs, args->report); !written) {
      exit_code = report_error("interpolate", written.error());
      return;
    }
    if (Status committed = outputs.commit(); !committed) {
      exit_code = report_error("interpolate", committed.error());
      return;
    }
    if (args->json) {
      print_json(json);
      return;
    }
    print_interpolation_table(json, args->program, args->out);
  });
}

}  // namespace pkm::cli
