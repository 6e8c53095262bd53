// pkm play DIR_OR_FILE [--periods N] [--to FILE|-] [--realtime] [--json]: releases the drive steps of a
// steps.bin at their servo rate, as a controller's real-time loop would
// (interpolation/drive_output/realtime_player.hpp), optionally passing each period on as a text line, and
// reports how punctually this computer kept the beat.
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <iostream>
#include <limits>
#include <system_error>

#include "cli_common.hpp"
#include "commands.hpp"
#include "interpolation/drive_output/realtime_player.hpp"
#include "interpolation/drive_output/step_stream.hpp"
#include "interpolation/drive_output/steps_csv.hpp"
#include "io/atomic_file.hpp"
#include "io/json_text.hpp"
#include "number_options.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

namespace {

using interpolation::StepPeriod;

// Each released period as a steps.csv row (after the same header line). To a FIFO, a device or stdout the
// row is written when the period is released (one write each, so the reader at the other end sees it at
// once); a regular file is staged and appears only when the whole run has been played.
class PlayLineSink : public interpolation::StepSink {
 public:
  PlayLineSink() = default;
  ~PlayLineSink() override {
    if (descriptor_ > STDERR_FILENO) ::close(descriptor_);
  }
  PlayLineSink(const PlayLineSink&) = delete;
  PlayLineSink& operator=(const PlayLineSink&) = delete;

  /// `target`: empty for nowhere, "-" for stdout, else a path. Opening a FIFO waits for its reader.
  Status open(const std::string& target, int actuators) {
    target_ = target;
    actuators_ = actuators;
    if (target.empty()) return ok_status();
    if (target == "-") {
      descriptor_ = STDOUT_FILENO;
    } else {
      struct stat status {};
      const bool exists = ::stat(target.c_str(), &status) == 0;
      if (exists && S_ISDIR(status.st_mode)) return failure(EISDIR);
      if (exists && (S_ISFIFO(status.st_mode) || S_ISCHR(status.st_mode))) {
        descriptor_ = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
        if (descriptor_ < 0) return failure(errno);
      } else {
        staged_ = true;
        if (auto opened = file_.open(target); !opened) return opened;
      }
    }
    return put(interpolation::steps_csv_header(actuators));
  }
  Status write(const StepPeriod& period) override {
    if (target_.empty()) return ok_status();
    interpolation::StepRowBuffer row;
    return put(interpolation::format_step_row(period, actuators_, row));
  }
  Status finish() override { return staged_ ? file_.commit() : ok_status(); }

 private:
  Error failure(int error_number) const {
    return make_error(ErrorCode::io,
                      fmt::format("cannot write {}: {}", target_,
                                  std::error_code(error_number, std::generic_category()).message()));
  }
  Status put(std::string_view text) {
    if (staged_) return file_.write(text);
    while (!text.empty()) {
      const ssize_t written = ::write(descriptor_, text.data(), text.size());
      if (written < 0 && errno == EINTR) continue;
      if (written < 0) return failure(errno);
      text.remove_prefix(static_cast<std::size_t>(written));
    }
    return ok_status();
  }

  std::string target_;
  int actuators_ = 0;
  int descriptor_ = -1;
  bool staged_ = false;
  StagedFile file_;
};

nlohmann::json play_json(const interpolation::PlayerStatistics& s,
                         const interpolation::StepStreamHeader& header, const std::string& file) {
  return {{"file", file},
          {"actuators", header.actuators},
          {"period_s", header.period_s},
          {"periods", s.periods},
          {"max_lateness_us", s.max_lateness_us},
          {"mean_lateness_us", s.mean_lateness_us},
          {"p99_lateness_us", s.p99_lateness_us},
          {"min_lateness_us", s.min_lateness_us},
          {"lateness_count", s.lateness.count},
          {"lateness_us_p50", s.lateness.p50_us},
          {"lateness_us_p99", s.lateness.p99_us},
          {"lateness_us_p99_9", s.lateness.p99_9_us},
          {"lateness_us_max", s.lateness.max_us},
          {"overruns", s.overruns},
          {"memory_locked", s.memory_locked},
          {"realtime_priority", s.realtime_priority},
          {"wall_time_s", s.wall_time_s}};
}

}  // namespace

void add_play_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "play", "release the drive steps of a steps.bin at the servo rate and measure the jitter");
  auto input = std::make_shared<std::string>();
  auto to = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto settings = std::make_shared<interpolation::PlayerSettings>();
  cmd->add_option("input", *input, "a directory with steps.bin, or a step stream file")->required();
  cmd->add_option("--periods", settings->max_periods, "play only the first N periods")
      ->check(number_in({0.0, 1e15, true, true, "", true}));
  cmd->add_option("--to", *to, "write each period as a steps.csv row to FILE, a FIFO, or - (stdout)");
  cmd->add_flag("--realtime", settings->try_realtime,
                "try to lock memory and run SCHED_FIFO (reported; usually refused without privileges)");
  cmd->add_flag("--json", *json, "print the statistics as JSON");
  cmd->callback([=, &exit_code] {
    std::error_code error;
    const std::string path =
        std::filesystem::is_directory(*input, error) ? interpolation::step_stream_path(*input) : *input;
    interpolation::StepStreamReader reader;
    if (auto opened = reader.open(path); !opened) {
      exit_code = report_error("play", opened.error());
      return;
    }
    // A reader that closes the FIFO must give an error, not end the process.
    std::signal(SIGPIPE, SIG_IGN);
    PlayLineSink sink;
    if (auto opened = sink.open(*to, reader.header().actuators); !opened) {
      exit_code = report_error("play", opened.error());
      return;
    }
    ProgressDisplay progress("play", "releasing the steps at the servo rate");
    auto played = interpolation::play(reader, sink, *settings);
    progress.finish();
    if (!played) {
      exit_code = report_error("play", played.error());
      return;
    }
    // With the periods on stdout, the statistics go to stderr so that stdout stays one CSV.
    std::ostream& out = *to == "-" ? std::cerr : std::cout;
    const interpolation::StepStreamHeader& header = reader.header();
    if (*json) {
      out << json_text(play_json(*played, header, path)) << "\n";
      return;
    }
    const interpolation::PlayerStatistics& s = *played;
    out << fmt::format("{}: {} actuators, {} periods of {:g} µs ({:g} Hz){}\n", path, header.actuators,
                       reader.period_count(), header.period_s * 1e6, 1.0 / header.period_s,
                       header.machine.empty() ? "" : ", machine " + header.machine);
    out << fmt::format("  played            {} periods in {:.3f} s\n", s.periods, s.wall_time_s);
    out << fmt::format(
        "  lateness          p50 {:.1f} µs, p99 {:.1f} µs, p99.9 {:.1f} µs, max {:.1f} µs, mean {:.1f} µs "
        "(after the deadline)\n",
        s.lateness.p50_us, s.lateness.p99_us, s.lateness.p99_9_us, s.lateness.max_us, s.mean_lateness_us);
    out << fmt::format("  overruns          {} (later than one period)\n", s.overruns);
    out << fmt::format("  memory locked     {}   SCHED_FIFO {}\n", s.memory_locked ? "yes" : "no",
                       s.realtime_priority ? "yes" : "no");
  });
}

}  // namespace pkm::cli
