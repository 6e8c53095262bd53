#include "workspace/modes_margin_program.hpp"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "planning/path_sampling.hpp"
#include "planning/servo_stream.hpp"

namespace pkm::workspace {
namespace {

// The ticks nearest to k·T/(samples + 1), k = 0 … samples + 1, without repeats (a short run has fewer ticks).
std::vector<long> margin_sample_ticks(long last_tick, int samples) {
  std::vector<long> ticks;
  const long intervals = static_cast<long>(samples) + 1;
  for (long k = 0; k <= intervals; ++k) {
    const long tick =
        std::lround(static_cast<double>(k) * static_cast<double>(last_tick) / static_cast<double>(intervals));
    if (ticks.empty() || tick != ticks.back()) ticks.push_back(tick);
  }
  return ticks;
}

}  // namespace

ModesMarginSummary summarise_modes_margin(const std::vector<ModesMarginSample>& samples) {
  ModesMarginSummary s;
  s.samples = static_cast<int>(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const ModesMarginSample& sample = samples[i];
    if (sample.margin.found) {
      ++s.margins_found;
      if (!sample.margin.note.empty()) ++s.margins_bounded;
      if (!s.min_margin || sample.margin.margin_mm < samples[*s.min_margin].margin.margin_mm)
        s.min_margin = i;
      if (!s.max_margin || sample.margin.margin_mm > samples[*s.max_margin].margin.margin_mm)
        s.max_margin = i;
    }
    const OtherAssemblyModes& modes = sample.modes;
    if (!modes.enumerated) {
      if (s.modes_note.empty()) s.modes_note = modes.note;
      continue;
    }
    ++s.modes_enumerated;
    s.min_real_modes = s.min_real_modes < 0 ? modes.real_modes : std::min(s.min_real_modes, modes.real_modes);
    s.max_real_modes = std::max(s.max_real_modes, modes.real_modes);
    if (!std::isnan(modes.nearest_other_distance_mm) &&
        (!s.nearest_other_mode ||
         modes.nearest_other_distance_mm < samples[*s.nearest_other_mode].modes.nearest_other_distance_mm)) {
      s.nearest_other_mode = i;
    }
  }
  return s;
}

Result<ProgramModesMargin> modes_margin_along_plan(const Machine& machine, const planning::MotionPlan& plan,
                                                   const ProgramModesMarginOptions& options) {
  if (options.samples < 1) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("samples must be at least 1 (poses between the start and the end), got {}",
                                  options.samples));
  }
  const Mechanism& mechanism = *machine.mechanism;
  if (mechanism.actuator_count() != mechanism.controlled_axes().count()) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("the assembly-mode margin needs a square actuator Jacobian; this {} has {} "
                                  "actuators for {} controlled coordinates",
                                  to_string(mechanism.type()), mechanism.actuator_count(),
                                  mechanism.controlled_axes().count()));
  }

  // The poses are the servo ticks `pkm plan` writes, with their program lines.
  ProgramModesMargin out;
  out.program_source = plan.program_source;
  out.duration_s = plan.duration_s;
  planning::ServoStream stream(plan, machine);
  const std::vector<long> ticks = margin_sample_ticks(stream.tick_count() - 1, options.samples);
  out.samples.reserve(ticks.size());
  planning::ServoTick tick;
  std::size_t next = 0;
  while (next < ticks.size() && stream.next(tick)) {
    if (tick.index != ticks[next]) continue;
    ModesMarginSample sample;
    sample.tick = tick.index;
    sample.time_s = tick.time_s;
    sample.line = tick.line;
    sample.margin.pose = tick.pose;
    sample.margin.actuators = tick.actuators;
    out.samples.push_back(sample);
    ++next;
  }
  if (stream.error()) return *stream.error();

  // Each sample is independent: in parallel, each written by one task only, so any thread count gives the
  // same numbers.
  std::vector<std::optional<Error>> failures(out.samples.size());
  const auto run = [&](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      ModesMarginSample& sample = out.samples[static_cast<std::size_t>(i)];
      auto margin = assembly_mode_margin(mechanism, sample.margin.pose, options.margin);
      if (!margin) {
        failures[static_cast<std::size_t>(i)] = margin.error();
        continue;
      }
      sample.margin = std::move(*margin);
      sample.modes = other_assembly_modes(mechanism, sample.margin.pose, sample.margin.actuators);
    }
  };
  const long count = static_cast<long>(out.samples.size());
  const int cores = tbb::info::default_concurrency();
  if (options.threads == 1 || cores == 1) {
    run(0, count);
  } else {
    tbb::task_arena arena(options.threads > 0 && options.threads < cores ? options.threads : cores);
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<long>(0, count, 1),
                        [&](const tbb::blocked_range<long>& r) { run(r.begin(), r.end()); });
    });
  }
  for (std::size_t i = 0; i < failures.size(); ++i) {
    if (!failures[i]) continue;
    const ModesMarginSample& sample = out.samples[i];
    return Error{
        failures[i]->code,
        fmt::format("{}:{}: at t = {:.3f} s, {}: {}", plan.program_source, sample.line, sample.time_s,
                    planning::program_pose_text(machine, sample.margin.pose), failures[i]->message),
        ErrorLocation{plan.program_source, sample.line, 0, ""}};
  }
  out.summary = summarise_modes_margin(out.samples);
  return out;
}

}  // namespace pkm::workspace
