#include "interpolation/plan_window_feed.hpp"

#include <algorithm>

namespace pkm::interpolation {

namespace {
constexpr double kKeptBehind = 1.0;  // path units (mm; deg along moves that only rotate)
}  // namespace

PlanWindowFeed::PlanWindowFeed(planning::StreamedPlan& streamed, const Machine& machine, IdealTiming& timing,
                               StrutLaws& laws)
    : streamed_(streamed),
      stream_(streamed.plan, machine, streamed.source.get()),
      timing_(timing),
      laws_(laws) {
  stream_.hold_path_from(0);
}

Status PlanWindowFeed::take_tick() {
  planning::ServoTick tick;
  if (!stream_.next(tick)) {
    if (stream_.error()) return *stream_.error();
    timing_.finish(streamed_.plan.path.length());
    return laws_.finish();
  }
  timing_.append(tick.s);
  peak_ticks_ = std::max(peak_ticks_, timing_.held_ticks());
  peak_segments_ = std::max(peak_segments_, streamed_.plan.path.segments.size());
  // The segments before the tick's are final: the plan has reached past them.
  if (tick.segment > laws_.fitted_end()) {
    if (Status fitted = laws_.fit_through(tick.segment); !fitted) return fitted;
    peak_pieces_ = std::max(peak_pieces_, laws_.held_pieces());
  }
  return ok_status();
}

Status PlanWindowFeed::advance(double tau_s, double lead_s) {
  const double ahead = tau_s + lead_s;
  while (!timing_.finished()) {
    if (timing_.covered_s() >= ahead && timing_.s_at(ahead) < laws_.length()) break;
    if (Status taken = take_tick(); !taken) return taken;
  }
  return ok_status();
}

void PlanWindowFeed::release_behind(double s, double tau_s) {
  const planning::MotionPlan& plan = streamed_.plan;
  if (plan.path.segments.empty()) return;
  // The segment a path unit behind s stays, and the one before it: the contour gauge's and the corrector's
  // searches start from their last hints and may step back a little (µm) from the period's start.
  const int keep = std::max(plan.path.segment_base, plan.path.find_segment(s - kKeptBehind, hint_) - 1);
  hint_ = keep;
  stream_.hold_path_from(keep);
  laws_.drop_before(keep);
  timing_.drop_before(tau_s);
}

}  // namespace pkm::interpolation
