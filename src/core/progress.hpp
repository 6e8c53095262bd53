#pragma once
// What a long computation tells whoever watches it: the phase it is in, how far it has come and the program
// line at work, and for a run streamed to files the servo ticks written so far. The computation only reports;
// drawing (a bar on a terminal, a log line) is the caller's. Callers of a sink report now and then (every few
// thousand ticks or samples), never per tick: a sink may take a lock.
#include <functional>
#include <string_view>

namespace pkm {

struct ProgressStep {
  std::string_view phase;  ///< what is being done, e.g. "planning", "writing actuators.csv"
  double fraction = -1.0;  ///< 0…1; negative when the phase cannot tell how far it is
  int line = 0;            ///< the program line being worked on; 0: none
  long ticks = -1;         ///< the servo ticks written so far; negative when the phase writes none
};

using ProgressSink = std::function<void(const ProgressStep&)>;

/// Reports to `sink` when there is one.
inline void report_progress(const ProgressSink& sink, std::string_view phase, double fraction = -1.0,
                            int line = 0, long ticks = -1) {
  if (sink) sink(ProgressStep{phase, fraction, line, ticks});
}

}  // namespace pkm
