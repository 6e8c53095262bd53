#pragma once
// The interpolator's inputs along a plan made while it streams (planning/plan_producer.hpp): the plan's
// ticks become the ideal timing, the path segments the ticks have passed (final then) get their strut laws,
// both ahead of the interpolator by a lead, and what lies behind it is forgotten: timing, laws, and the
// plan's path and samples. Memory is then bounded by the planner's look-ahead and the lead, not by the
// program, and the periods are those of the whole plan's run (the same ticks, the same laws).
#include "core/result.hpp"
#include "interpolation/methods/ideal_timing.hpp"
#include "interpolation/methods/strut_laws.hpp"
#include "planning/plan_producer.hpp"
#include "planning/servo_stream.hpp"

namespace pkm::interpolation {

class PlanWindowFeed {
 public:
  /// `streamed`, `timing` (an open IdealTiming::window) and `laws` (a StrutLaws::window on streamed.plan's
  /// path) outlive the feed.
  PlanWindowFeed(planning::StreamedPlan& streamed, const Machine& machine, IdealTiming& timing,
                 StrutLaws& laws);
  /// Before a period from ideal time τ: the timing reaches τ + `lead_s` (or the plan's end) and the laws the
  /// path parameter it gives there. Errors: the plan's (a tick out of reach, the bound on the ticks).
  Status advance(double tau_s, double lead_s);
  /// Nothing before path parameter `s` and ideal time `tau_s` is looked at again.
  void release_behind(double s, double tau_s);

  /// The most ticks of timing, strut-law pieces and path segments held at once so far.
  std::size_t peak_ticks() const { return peak_ticks_; }
  std::size_t peak_pieces() const { return peak_pieces_; }
  std::size_t peak_segments() const { return peak_segments_; }

 private:
  Status take_tick();

  planning::StreamedPlan& streamed_;
  planning::ServoStream stream_;
  IdealTiming& timing_;
  StrutLaws& laws_;
  int hint_ = 0;
  std::size_t peak_ticks_ = 0, peak_pieces_ = 0, peak_segments_ = 0;
};

}  // namespace pkm::interpolation
