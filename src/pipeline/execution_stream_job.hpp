#pragma once
// `pkm linuxcnc stream` as one library call: a part program planned for execution on a controller and
// interpolated to whole drive steps, written as the execution stream (formats/execution_stream.hpp) period by
// period while it is computed, for pkm's HAL component to execute in LinuxCNC's servo thread.
//
// The plan leaves the drives the headroom that execution needs (execution/execution_headroom.hpp): at any
// feed override up to the largest, with a feed hold or an abort at any period, the executed motion stays
// within the machine file's speed and acceleration limits. pkmexec computes the same headroom from the same
// machine file, so both ends agree on how fast the override may change.
#include <optional>
#include <string>

#include "core/progress.hpp"
#include "execution/machine_headroom.hpp"
#include "interpolation/interpolate_run.hpp"
#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"

namespace pkm::pipeline {

struct ExecutionStreamJob {
  std::string program_path;
  ProgramOptions program_options;
  std::string target = "-";  ///< "-": standard output, else a file
  /// Also the interpolation's own output set there (steps.csv, steps.bin, contour.csv, summary.json): the
  /// record of what was streamed. Empty: none.
  std::string out_directory;
  std::optional<double> period_ms;
  std::optional<double> step;
  ProgressSink progress;
};

struct ExecutionStreamResult {
  interpolation::InterpolateSummary summary;
  execution::ExecutionHeadroom headroom;  ///< in the actuators' units (mm/s, mm/s², or rad)
};

/// Plans `machine` within the headroom (its limits are changed to the nominal ones) and streams.
Result<ExecutionStreamResult> stream_for_execution(Machine machine, const ExecutionStreamJob& job);

}  // namespace pkm::pipeline
