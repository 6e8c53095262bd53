#pragma once
// `pkm play` as one library call: the drive steps of a steps.bin released at their servo rate, as a
// controller's real-time loop would (interpolation/drive_output/realtime_player.hpp), each period optionally
// passed on as a steps.csv row (formats/step_line_sink.hpp), with how punctually this computer kept the beat.
#include <string>

#include "interpolation/drive_output/realtime_player.hpp"
#include "interpolation/drive_output/step_stream.hpp"

namespace pkm::pipeline {

struct PlayJob {
  std::string input;  ///< a directory with steps.bin, or a step stream file
  /// Where each released period goes as a steps.csv row: empty nowhere, "-" stdout, else a file, a FIFO
  /// (opening it waits for its reader) or a device. A reader that closes a FIFO or a pipe raises SIGPIPE: a
  /// caller that wants the error instead ignores that signal.
  std::string to;
  interpolation::PlayerSettings settings;
};

struct PlayJobResult {
  std::string path;  ///< the stream played
  interpolation::StepStreamHeader header;
  long period_count = 0;  ///< the periods in the stream
  interpolation::PlayerStatistics statistics;
};

/// Refuses a stream that is missing or damaged (naming the file) and a target that cannot be written.
Result<PlayJobResult> run_play_job(const PlayJob& job);

}  // namespace pkm::pipeline
