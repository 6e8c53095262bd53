#include "progress_display.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <iostream>

#include "output_options.hpp"

namespace pkm::cli {

namespace {

ProgressMode g_progress_mode = ProgressMode::automatic;
// The display that is running: one at a time, on the command's thread.
ProgressDisplay* g_active_display = nullptr;

// The commands that can run for seconds on a real program or grid: they show the progress line.
constexpr std::array<std::string_view, 14> kLongCommands{"plan",
                                                         "interpolate",
                                                         "play",
                                                         "servo",
                                                         "optimize",
                                                         "report",
                                                         "stiffness",
                                                         "compliance",
                                                         "modes-margin",
                                                         "workspace",
                                                         "strategies",
                                                         "calibrate plan",
                                                         "calibrate simulate",
                                                         "calibrate identify"};

// Terminals are redrawn in place; the first second stays quiet so that short commands print nothing.
constexpr double kQuietStartS = 1.0;
// Lines (--progress always) at every phase change and at most this often within a phase.
constexpr double kLineEveryS = 5.0;
constexpr auto kTickPeriod = std::chrono::milliseconds(250);

}  // namespace

void add_progress_options(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    add_progress_options(*sub);
    const std::string name = full_command_name(*sub);
    for (const std::string_view command : kLongCommands) {
      if (name != command) continue;
      sub->add_option_function<std::string>(
             "--progress",
             [](const std::string& value) {
               g_progress_mode = value == "always"  ? ProgressMode::always
                                 : value == "never" ? ProgressMode::never
                                                    : ProgressMode::automatic;
             },
             "the progress line on stderr: auto (on a terminal, after the first second), always (as lines, "
             "for logs), never")
          ->check(CLI::IsMember({"auto", "always", "never"}));
    }
  }
}

std::string clock_text(double seconds) {
  const long total = std::lround(std::max(0.0, seconds));
  if (total >= 3600) return fmt::format("{}:{:02}:{:02}", total / 3600, total / 60 % 60, total % 60);
  return fmt::format("{}:{:02}", total / 60, total % 60);
}

std::string ticks_text(long ticks) {
  if (ticks == 1) return "1 tick";
  if (ticks < 10'000) return fmt::format("{} ticks", ticks);
  if (ticks < 999'950) return fmt::format("{:.1f} k ticks", static_cast<double>(ticks) / 1e3);
  return fmt::format("{:.1f} M ticks", static_cast<double>(ticks) / 1e6);
}

std::string progress_text(const ProgressStep& step, double elapsed_s, double phase_elapsed_s) {
  std::string text(step.phase);
  const bool known = step.fraction >= 0.0;
  const double fraction = std::min(1.0, step.fraction);
  if (known) {
    constexpr int width = 20;
    const int filled = static_cast<int>(fraction * width);
    text += fmt::format("  [{}{}] {:3.0f} %", std::string(static_cast<std::size_t>(filled), '#'),
                        std::string(static_cast<std::size_t>(width - filled), '.'), fraction * 100.0);
  }
  if (step.line > 0) text += fmt::format("  line {}", step.line);
  if (step.ticks >= 0) text += "  " + ticks_text(step.ticks);
  text += fmt::format("  {} elapsed", clock_text(elapsed_s));
  // The phase's own rate so far: a phase that started late is not charged for the ones before it.
  if (known && fraction >= 0.01 && fraction < 1.0 && phase_elapsed_s >= 0.5)
    text += fmt::format("  {} left", clock_text(phase_elapsed_s * (1.0 - fraction) / fraction));
  return text;
}

ProgressDisplay::ProgressDisplay(std::string command, std::string_view first_phase)
    : command_(std::move(command)), mode_(g_progress_mode), phase_(first_phase) {
  if (mode_ == ProgressMode::automatic && isatty(STDERR_FILENO) == 0) mode_ = ProgressMode::never;
  if (mode_ == ProgressMode::never) return;
  // As lines, the first phase is written before the computation starts, whatever the ticker's start.
  if (mode_ == ProgressMode::always) draw(true);
  ticker_ = std::thread([this] { tick(); });
  g_active_display = this;
}

void finish_active_progress() {
  if (g_active_display != nullptr) g_active_display->finish();
}

ProgressDisplay::~ProgressDisplay() {
  finish();
}

ProgressSink ProgressDisplay::sink() {
  if (mode_ == ProgressMode::never) return {};
  return [this](const ProgressStep& step) { update(step); };
}

void ProgressDisplay::update(const ProgressStep& step) {
  const std::lock_guard lock(mutex_);
  const bool new_phase = step.phase != phase_;
  if (new_phase) {
    phase_.assign(step.phase);
    phase_started_ = Clock::now();
    phase_changed_ = true;
  }
  fraction_ = step.fraction;
  // A phase that names no line keeps the one it last named; a new phase starts without one.
  if (step.line > 0 || new_phase) line_ = step.line;
  // Likewise the ticks written: a phase that tells none keeps the count it last told.
  if (step.ticks >= 0 || new_phase) ticks_ = step.ticks;
}

void ProgressDisplay::tick() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    draw(mode_ == ProgressMode::always);
    wake_.wait_for(lock, kTickPeriod, [this] { return stop_; });
  }
}

void ProgressDisplay::draw(bool as_line) {
  const Clock::time_point now = Clock::now();
  const double elapsed_s = std::chrono::duration<double>(now - started_).count();
  const double phase_s = std::chrono::duration<double>(now - phase_started_).count();
  const std::string text =
      fmt::format("pkm {}: {}", command_,
                  progress_text(ProgressStep{phase_, fraction_, line_, ticks_}, elapsed_s, phase_s));
  if (as_line) {
    if (!phase_changed_ && std::chrono::duration<double>(now - last_line_).count() < kLineEveryS) return;
    std::cerr << text << "\n" << std::flush;
    last_line_ = now;
  } else {
    if (elapsed_s < kQuietStartS) return;
    std::cerr << "\r" << text << "\033[K" << std::flush;
    drawn_ = true;
  }
  phase_changed_ = false;
}

void ProgressDisplay::finish() {
  if (g_active_display == this) g_active_display = nullptr;
  {
    const std::lock_guard lock(mutex_);
    if (stop_ && !ticker_.joinable()) return;
    // As lines, where the command ended is written even when it came between two ticks.
    if (mode_ == ProgressMode::always && ticker_.joinable()) {
      phase_changed_ = true;
      draw(true);
    }
    stop_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  if (drawn_) std::cerr << "\r\033[K" << std::flush;
  drawn_ = false;
}

}  // namespace pkm::cli
