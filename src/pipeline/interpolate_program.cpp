#include "pipeline/interpolate_program.hpp"

#include <fmt/format.h>

#include "core/units.hpp"
#include "formats/contour_trace.hpp"
#include "formats/interpolation_summary.hpp"
#include "interpolation/drive_output/step_stream.hpp"
#include "interpolation/drive_output/steps_csv.hpp"
#include "io/atomic_file.hpp"
#include "io/json_text.hpp"
#include "io/output_set.hpp"
#include "io/version.hpp"
#include "pipeline/load_program.hpp"
#include "pipeline/run_report.hpp"
#include "planning/motion_plan.hpp"

namespace pkm::pipeline {

namespace {

constexpr double kMinPeriodMs = 0.1;
constexpr double kMaxPeriodMs = 20.0;

// The job's drive parameters, completed from the machine file's `drives:` and checked.
Result<interpolation::InterpolateOptions> resolved_options(const Machine& machine,
                                                           const InterpolateJob& job) {
  interpolation::InterpolateOptions options = job.options;
  // The machine file's reader checks drives.period_ms the same way; this is for a period given in the job.
  const double period_ms = job.period_ms ? *job.period_ms : machine.drives.period_ms.value_or(1.0);
  if (!(period_ms >= kMinPeriodMs - 1e-9 && period_ms <= kMaxPeriodMs + 1e-9)) {
    return Error{ErrorCode::bad_input, fmt::format("servo period {} ms is outside {}…{} ms", period_ms,
                                                   kMinPeriodMs, kMaxPeriodMs)};
  }
  options.period_s = period_ms * 1e-3;
  const double step = job.step ? *job.step : machine.drives.step.value_or(0.001);
  if (!(step > 0.0)) {
    return Error{ErrorCode::bad_input,
                 fmt::format("drive step {} must be a positive resolution (mm per step)", step)};
  }
  options.step_mm = step;
  const std::optional<double> rate =
      job.max_step_rate_hz ? job.max_step_rate_hz : machine.drives.max_step_rate_hz;
  if (rate && *rate > 0.0) options.max_step_rate_hz = *rate;
  // Changes are percentages of the programmed feed; the plan already runs at the starting override.
  options.feed_override.changes = job.override_changes;
  for (auto& change : options.feed_override.changes) change.percent *= 100.0 / job.override_pct;
  options.feed_override.shape = job.accel;
  options.feed_override.full_ramp_s =
      (machine.motion.max_feed_mm_min / 60.0) / machine.motion.path_accel_mm_s2;
  return options;
}

}  // namespace

Result<InterpolateProgramResult> interpolate_program(const Machine& machine, const InterpolateJob& job) {
  auto options = resolved_options(machine, job);
  if (!options) return options.error();
  report_progress(job.progress, "reading the program");
  auto program = load_program_for(machine, job.program_path, job.program_options);
  if (!program) return program.error();
  planning::PlanOptions plan_options;
  plan_options.rate_hz = 1.0 / options->period_s;
  plan_options.override_pct = job.override_pct;
  // The linear law has no jerk limit: trapezoidal path speed.
  plan_options.jerk_limited = job.accel != interpolation::RampShape::linear;
  plan_options.progress = job.progress;
  auto plan = planning::plan_motion(machine, *program, plan_options);
  if (!plan) return plan.error();
  auto timing = interpolation::IdealTiming::from_plan(*plan, machine);
  if (!timing) return timing.error();

  options->progress = job.progress;
  const bool files = !job.out_directory.empty();
  if (!files && !job.report_path.empty()) {
    return make_error(ErrorCode::bad_input, "an interpolation report needs an output directory");
  }
  // The step files, the contour trace, the summary and the report replace the previous run's together.
  OutputSet outputs{"interpolate"};
  interpolation::StepsCsvWriter csv;
  interpolation::StepStreamWriter binary;
  formats::ContourTraceWriter trace;
  std::vector<interpolation::StepSink*> sinks;
  if (files) {
    if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
    interpolation::StepStreamHeader header;
    header.actuators = machine.mechanism->actuator_count();
    header.period_s = options->period_s;
    // The stream's step is in the actuators' own unit: mm, or rad for angular actuators (given in deg).
    header.step_mm =
        machine.mechanism->actuators_are_angles() ? options->step_mm * (kPi / 180.0) : options->step_mm;
    header.machine = machine.source;
    auto start_steps = interpolation::start_positions(machine, plan->path, options->step_mm);
    if (!start_steps) return start_steps.error();
    header.start_position = *start_steps;
    if (Status opened = csv.open(outputs.staged_path("steps.csv"), header); !opened) return opened.error();
    if (Status opened = binary.open(outputs.staged_path("steps.bin"), header); !opened) return opened.error();
    if (Status opened = trace.open(outputs.staged_path("contour.csv")); !opened) return opened.error();
    sinks = {&csv, &binary};
  }
  Status trace_status = ok_status();
  options->on_period = [&](const interpolation::StepPeriod& period,
                           const interpolation::PeriodContour& contour, const Eigen::Vector3d& path_mm) {
    if (job.on_period) job.on_period(period, contour, path_mm);
    if (files && trace_status) trace_status = trace.add(period, contour, path_mm);
  };
  auto summary = interpolation::interpolate(machine, plan->path, *timing, *options, sinks, program->source);
  if (!summary) return summary.error();
  if (files && trace_status) trace_status = trace.finish();
  if (!trace_status) return trace_status.error();

  InterpolateProgramResult result;
  result.blocks = plan->statistics.blocks;
  result.json = formats::interpolation_summary_json(*summary, machine);
  result.json["program"] = program->source;
  result.json["pkm_version"] = std::string(pkm_version());
  result.json["blocks"] = plan->statistics.blocks;
  result.json["override_pct"] = job.override_pct;
  result.json["accel"] = job.accel == interpolation::RampShape::linear ? "linear" : "s-curve";
  if (options->max_step_rate_hz) result.json["max_step_rate_hz"] = *options->max_step_rate_hz;
  if (files) {
    if (Status written =
            write_file_atomically(outputs.staged_path("summary.json"), json_text(result.json) + "\n");
        !written) {
      return written.error();
    }
    if (!job.report_path.empty()) report_progress(job.progress, "writing the report");
    if (Status written = stage_run_report(outputs, job.report_path); !written) return written.error();
    if (Status committed = outputs.commit(); !committed) return committed.error();
  }
  result.summary = std::move(*summary);
  return result;
}

}  // namespace pkm::pipeline
