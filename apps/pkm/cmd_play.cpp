// pkm play DIR_OR_FILE [--periods N] [--to FILE|-] [--realtime] [--json]: releases the drive steps of a
// steps.bin at their servo rate, as a controller's real-time loop would
// (pipeline/play_job.hpp), optionally passing each period on as a text line, and reports how punctually this
// computer kept the beat.
#include <fmt/format.h>

#include <csignal>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/json_text.hpp"
#include "number_options.hpp"
#include "pipeline/play_job.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

namespace {

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

void print_play(std::ostream& out, const pipeline::PlayJobResult& played) {
  const interpolation::StepStreamHeader& header = played.header;
  const interpolation::PlayerStatistics& s = played.statistics;
  out << fmt::format("{}: {} actuators, {} periods of {:g} µs ({:g} Hz){}\n", played.path, header.actuators,
                     played.period_count, header.period_s * 1e6, 1.0 / header.period_s,
                     header.machine.empty() ? "" : ", machine " + header.machine);
  out << fmt::format("  played            {} periods in {:.3f} s\n", s.periods, s.wall_time_s);
  out << fmt::format(
      "  lateness          p50 {:.1f} µs, p99 {:.1f} µs, p99.9 {:.1f} µs, max {:.1f} µs, mean {:.1f} µs "
      "(after the deadline)\n",
      s.lateness.p50_us, s.lateness.p99_us, s.lateness.p99_9_us, s.lateness.max_us, s.mean_lateness_us);
  out << fmt::format("  overruns          {} (later than one period)\n", s.overruns);
  out << fmt::format("  memory locked     {}   SCHED_FIFO {}\n", s.memory_locked ? "yes" : "no",
                     s.realtime_priority ? "yes" : "no");
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
    // A reader that closes the FIFO must give an error, not end the process.
    std::signal(SIGPIPE, SIG_IGN);
    ProgressDisplay progress("play", "releasing the steps at the servo rate");
    auto played = pipeline::run_play_job({*input, *to, *settings});
    progress.finish();
    if (!played) {
      exit_code = report_error("play", played.error());
      return;
    }
    // With the periods on stdout, the statistics go to stderr so that stdout stays one CSV.
    std::ostream& out = *to == "-" ? std::cerr : std::cout;
    if (*json)
      out << json_text(play_json(played->statistics, played->header, played->path)) << "\n";
    else
      print_play(out, *played);
  });
}

}  // namespace pkm::cli
