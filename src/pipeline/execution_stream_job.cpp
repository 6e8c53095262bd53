#include "pipeline/execution_stream_job.hpp"

#include <fmt/format.h>

#include "formats/execution_stream.hpp"
#include "pipeline/interpolate_program.hpp"

namespace pkm::pipeline {

Result<ExecutionStreamResult> stream_for_execution(Machine machine, const ExecutionStreamJob& job) {
  const double period_s = job.period_ms.value_or(machine.drives.period_ms.value_or(1.0)) * 1e-3;
  auto headroom = execution::machine_headroom(machine, period_s);
  if (!headroom) return headroom.error();
  machine.limits.speed = headroom->nominal.speed;
  machine.limits.accel = headroom->nominal.accel;

  formats::ExecutionStreamWriter writer;
  const double step = job.step.value_or(machine.drives.step.value_or(0.001));
  if (Status opened =
          writer.open(job.target, machine.source, machine.mechanism->actuator_count(), period_s, step);
      !opened)
    return opened.error();
  Status written = ok_status();
  InterpolateJob interpolate;
  interpolate.program_path = job.program_path;
  interpolate.program_options = job.program_options;
  interpolate.period_ms = period_s * 1e3;
  interpolate.step = step;
  interpolate.progress = job.progress;
  interpolate.out_directory = job.out_directory;
  interpolate.on_period = [&](const interpolation::StepPeriod& period, const interpolation::PeriodContour&,
                              const Eigen::Vector3d&) {
    if (written) written = writer.write(period);
  };
  auto run = interpolate_program(machine, interpolate);
  if (!run) return run.error();  // no `end` line: the controller stops after the last period it has
  if (!written) return written.error();
  if (Status finished = writer.finish(); !finished) return finished.error();
  return ExecutionStreamResult{std::move(run->summary), *headroom};
}

}  // namespace pkm::pipeline
