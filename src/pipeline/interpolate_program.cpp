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
#include "pipeline/program_stream.hpp"
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

// What the run goes along: for the carrier methods, a plan made while the program is read, streamed twice
// (checked, then interpolated) so that memory does not grow with the program; for the estimating method, the
// whole plan.
struct RunInputs {
  std::string source;
  StreamedProgramPlan streamed;
  interpolation::StreamedPlanCheck check;
  std::unique_ptr<program::CanonicalProgram> program;
  std::optional<planning::MotionPlan> whole;
  std::optional<interpolation::IdealTiming> timing;

  const planning::MotionPlan& plan() const { return whole ? *whole : streamed.plan->plan; }
};

planning::PlanOptions plan_options_for(const InterpolateJob& job,
                                       const interpolation::InterpolateOptions& options) {
  planning::PlanOptions plan_options;
  plan_options.rate_hz = 1.0 / options.period_s;
  plan_options.override_pct = job.override_pct;
  // The linear law has no jerk limit: trapezoidal path speed.
  plan_options.jerk_limited = job.accel != interpolation::RampShape::linear;
  plan_options.progress = job.progress;
  return plan_options;
}

Status prepare_whole(const Machine& machine, const InterpolateJob& job,
                     const interpolation::InterpolateOptions& options, RunInputs& inputs) {
  report_progress(job.progress, "reading the program");
  auto program = load_program_for(machine, job.program_path, job.program_options);
  if (!program) return program.error();
  inputs.program = std::make_unique<program::CanonicalProgram>(std::move(*program));
  inputs.source = inputs.program->source;
  auto plan = planning::plan_motion(machine, *inputs.program, plan_options_for(job, options));
  if (!plan) return plan.error();
  inputs.whole = std::move(*plan);
  auto timing = interpolation::IdealTiming::from_plan(*inputs.whole, machine);
  if (!timing) return timing.error();
  inputs.timing = std::move(*timing);
  return ok_status();
}

// The first stream checks every tick of the plan (nothing moves for a program that breaks a limit) and finds
// δρ_max along the path; the second, from a fresh read of the program, is the one interpolated.
Status prepare_streamed(const Machine& machine, const InterpolateJob& job,
                        const interpolation::InterpolateOptions& options, RunInputs& inputs) {
  report_progress(job.progress, "checking the plan");
  const planning::PlanOptions plan_options = plan_options_for(job, options);
  {
    auto first = start_streamed_program_plan(machine, job.program_path, job.program_options, plan_options);
    if (!first) return first.error();
    auto check = interpolation::check_streamed_plan(machine, *first->plan, options.amplification_spacing,
                                                    first->program->source, job.progress);
    if (!check) return check.error();
    inputs.check = *check;
  }
  auto second = start_streamed_program_plan(machine, job.program_path, job.program_options, plan_options);
  if (!second) return second.error();
  inputs.streamed = std::move(*second);
  inputs.source = inputs.streamed.program->source;
  return ok_status();
}

// The summary (and the report) after the run, committed with its step files.
Result<InterpolateProgramResult> finish_interpolation(const Machine& machine, const InterpolateJob& job,
                                                      const RunInputs& inputs,
                                                      const interpolation::InterpolateOptions& options,
                                                      interpolation::InterpolateSummary summary,
                                                      OutputSet& outputs) {
  const bool files = !job.out_directory.empty();
  InterpolateProgramResult result;
  result.blocks = inputs.plan().statistics.blocks;
  result.json = formats::interpolation_summary_json(summary, machine);
  result.json["program"] = inputs.source;
  result.json["pkm_version"] = std::string(pkm_version());
  result.json["blocks"] = result.blocks;
  result.json["override_pct"] = job.override_pct;
  result.json["accel"] = job.accel == interpolation::RampShape::linear ? "linear" : "s-curve";
  if (options.max_step_rate_hz) result.json["max_step_rate_hz"] = *options.max_step_rate_hz;
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
  result.summary = std::move(summary);
  return result;
}

}  // namespace

Result<InterpolateProgramResult> interpolate_program(const Machine& machine, const InterpolateJob& job) {
  auto options = resolved_options(machine, job);
  if (!options) return options.error();
  const bool files = !job.out_directory.empty();
  if (!files && !job.report_path.empty()) {
    return make_error(ErrorCode::bad_input, "an interpolation report needs an output directory");
  }
  RunInputs inputs;
  const bool whole = options->method == interpolation::Method::estimating;
  if (Status prepared = whole ? prepare_whole(machine, job, *options, inputs)
                              : prepare_streamed(machine, job, *options, inputs);
      !prepared)
    return prepared.error();
  options->progress = job.progress;
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
    auto start_steps = interpolation::start_positions(machine, inputs.plan().path, options->step_mm);
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
  auto summary = whole ? interpolation::interpolate(machine, inputs.whole->path, *inputs.timing, *options,
                                                    sinks, inputs.source)
                       : interpolation::interpolate_streamed(machine, *inputs.streamed.plan, inputs.check,
                                                             *options, sinks, inputs.source);
  if (!summary) return summary.error();
  if (files && trace_status) trace_status = trace.finish();
  if (!trace_status) return trace_status.error();
  return finish_interpolation(machine, job, inputs, *options, std::move(*summary), outputs);
}

}  // namespace pkm::pipeline
