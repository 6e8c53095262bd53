#pragma once
// The progress line of the commands that can run for a while, on stderr:
//   pkm plan: planning  [########............]  41 %  line 4812  0:03 elapsed  0:04 left
//   pkm plan: writing the outputs  [####################]  98 %  line 5120  1.2 M ticks  0:09 elapsed
// A ticker redraws it four times a second from what the computation last told (core/progress.hpp), so that
// even a phase that reports nothing shows its name and the time it has taken: no command is silent for
// seconds. On a terminal it appears after the first second (short commands stay quiet) and is erased when
// the command ends; `--progress always` writes it as lines (for logs), `--progress never` not at all.
#include <CLI/CLI.hpp>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "core/progress.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

enum class ProgressMode { automatic, always, never };

/// Adds `--progress auto|always|never` to the commands that can run for seconds.
void add_progress_options(CLI::App& app);

/// The line's text (without the command): phase, bar and percentage when the fraction is known, the program
/// line, the servo ticks written (ticks_text), the elapsed time and, from the phase's own rate, the time left
/// in it.
std::string progress_text(const ProgressStep& step, double elapsed_s, double phase_elapsed_s);

/// "1 tick", "812 ticks", "48.1 k ticks", "1.2 M ticks": a count that stays short as it grows.
std::string ticks_text(long ticks);

/// "0:07", "12:03", "1:02:03".
std::string clock_text(double seconds);

/// Ends the progress line of the display that is running, if any (before an error message).
void finish_active_progress();

class ProgressDisplay {
 public:
  /// `first_phase`: the name shown until the computation tells another.
  ProgressDisplay(std::string command, std::string_view first_phase);
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  /// For the computation's jobs; valid while this display lives.
  ProgressSink sink();
  /// Stops the ticker and erases the line; call before printing the command's results.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  void update(const ProgressStep& step);
  void tick();
  void draw(bool as_line);

  std::string command_;
  ProgressMode mode_;
  Clock::time_point started_ = Clock::now();
  Clock::time_point phase_started_ = started_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string phase_;
  double fraction_ = -1.0;
  int line_ = 0;
  long ticks_ = -1;
  bool phase_changed_ = true;
  bool drawn_ = false;
  bool stop_ = false;
  Clock::time_point last_line_{};
  std::thread ticker_;
};

}  // namespace pkm::cli
