#include "planning/lookahead_profile.hpp"

#include <algorithm>
#include <cmath>

namespace pkm::planning {

namespace {

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
/// Samples pushed between two plannings of the window: each planning erodes and passes over the whole
/// window, so planning at every push would cost the window's length per sample.
constexpr std::size_t kPlanEvery = 512;
/// A full window is planned once this fraction of its samples more has come: it overshoots its bound by
/// that much at most, and a window that hands on only a few samples per planning is not planned per sample.
constexpr std::size_t kFullWindowSteps = 16;
/// History is dropped in batches once it is as long as the rest of the window (erasing the front of the
/// arrays moves the rest; every planning erodes the history too).
constexpr std::size_t kDropAtLeast = 64;

template <class T>
void erase_front(std::vector<T>& values, std::size_t count) {
  values.erase(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(count));
}

}  // namespace

LookaheadProfile::LookaheadProfile(const LookaheadSettings& settings) : settings_(settings) {
  reach_ = settings.filter_window_s * settings.fastest_cap + settings.erosion_margin;
  // A window shorter than a few reaches would never hold a sample with final caps.
  settings_.max_length = std::max(settings.max_length, 4.0 * reach_);
}

void LookaheadProfile::push(const RawSample& sample) {
  window_.s.push_back(sample.s);
  window_.speed_cap.push_back(sample.stop ? 0.0 : sample.speed_cap);
  window_.accel_cap.push_back(sample.accel_cap);
  window_.speed.push_back(0.0);
  window_.hold_s.push_back(sample.hold_s);
  window_.stop.push_back(sample.stop ? 1 : 0);
  raw_speed_cap_.push_back(window_.speed_cap.back());
  raw_accel_cap_.push_back(sample.accel_cap);
  move_.push_back(sample.move);
  peak_window_ = std::max(peak_window_, window_.size());
  ++pushed_since_advance_;
  if (pushed_since_advance_ >= kPlanEvery || (pushed_since_advance_ >= full_window_step_ && window_full()))
    advance(false);
}

void LookaheadProfile::finish() {
  advance(true);
}

std::size_t LookaheadProfile::last_final_caps(bool at_end) const {
  const std::size_t n = window_.size();
  if (at_end) return n - 1;
  // A later sample at s ≥ s_last spreads its cap back over samples j with s_{j+1} ≥ s_last − reach (the
  // spread takes one sample beyond its reach, speed_profile.cpp): the ones before are final.
  const auto beyond = std::lower_bound(window_.s.begin(), window_.s.end(), window_.s.back() - reach_);
  const std::size_t first_reached = static_cast<std::size_t>(beyond - window_.s.begin());
  return first_reached < 2 ? kNone : first_reached - 2;
}

bool LookaheadProfile::window_full() const {
  if (first_waiting_ >= window_.size()) return false;
  const std::size_t last = window_.size() - 1;
  const std::size_t waiting = last - first_waiting_ + 1;
  return window_.s[last] - window_.s[first_waiting_] >= settings_.max_length ||
         waiting >= settings_.max_samples || move_[last] - move_[first_waiting_] >= settings_.max_moves;
}

void LookaheadProfile::erode_window() {
  window_.speed_cap = raw_speed_cap_;
  window_.accel_cap = raw_accel_cap_;
  erode_caps(window_, settings_.filter_window_s, settings_.erosion_margin);
  // The sample handed on last keeps the caps it was planned with: the forward pass leaves it with them, and
  // the history that lowered them may be gone.
  if (first_waiting_ > 0) {
    window_.speed_cap[first_waiting_ - 1] = planned_caps_[0];
    window_.accel_cap[first_waiting_ - 1] = planned_caps_[1];
  }
}

/// The passes of plan_speeds over the waiting samples up to `last`, the forward one from the speed handed
/// on last, the backward one from a stop assumed at `last` (the path's real end when `at_end`). Returns the
/// last sample whose speed that assumed stop did not lower (final), or kNone.
std::size_t LookaheadProfile::plan_window(std::size_t last, bool at_end) {
  ProfileSamples& p = window_;
  const std::size_t start = first_waiting_;
  if (start == 0) p.speed[0] = 0.0;
  for (std::size_t i = std::max<std::size_t>(start, 1); i <= last; ++i) {
    const double a = std::min(p.accel_cap[i - 1], p.accel_cap[i]);
    const double reachable = std::sqrt(p.speed[i - 1] * p.speed[i - 1] + 2.0 * a * (p.s[i] - p.s[i - 1]));
    p.speed[i] = std::min(p.speed_cap[i], reachable);
  }
  std::size_t final_sample = at_end || p.speed[last] <= 0.0 ? last : kNone;
  p.speed[last] = 0.0;
  for (std::size_t i = last; i-- > start;) {
    const double a = std::min(p.accel_cap[i], p.accel_cap[i + 1]);
    const double brakeable = std::sqrt(p.speed[i + 1] * p.speed[i + 1] + 2.0 * a * (p.s[i + 1] - p.s[i]));
    if (brakeable < p.speed[i]) {
      p.speed[i] = brakeable;
    } else if (final_sample == kNone) {
      final_sample = i;
    }
  }
  return final_sample;
}

void LookaheadProfile::hand_on(std::size_t last) {
  for (std::size_t i = first_waiting_; i <= last; ++i) {
    planned_.push_back(PlannedSample{window_.s[i], window_.speed_cap[i], window_.accel_cap[i],
                                     window_.speed[i], window_.hold_s[i], window_.stop[i] != 0});
  }
  first_waiting_ = last + 1;
  planned_caps_ = {window_.speed_cap[last], window_.accel_cap[last]};
}

void LookaheadProfile::drop_history() {
  if (first_waiting_ == 0) return;
  // The spreads that reach the oldest waiting sample start at most `reach` behind the last final one.
  const double keep_from = window_.s[first_waiting_ - 1] - reach_;
  const auto kept = std::lower_bound(window_.s.begin(), window_.s.end(), keep_from);
  std::size_t drop = static_cast<std::size_t>(kept - window_.s.begin());
  drop = std::min(drop == 0 ? 0 : drop - 1, first_waiting_ - 1);
  if (drop < kDropAtLeast || 2 * drop < window_.size()) return;
  window_.erase_front(drop);
  erase_front(raw_speed_cap_, drop);
  erase_front(raw_accel_cap_, drop);
  erase_front(move_, drop);
  first_waiting_ -= drop;
}

void LookaheadProfile::advance(bool at_end) {
  pushed_since_advance_ = 0;
  if (first_waiting_ >= window_.size()) return;
  const std::size_t last = last_final_caps(at_end);
  if (last == kNone || last < first_waiting_) return;
  erode_window();
  std::size_t final_sample = plan_window(last, at_end);
  const bool found = final_sample != kNone && final_sample >= first_waiting_;
  if (!at_end && last > first_waiting_ && window_full()) {
    // Full: at least the window's first quarter is handed on, as planned to stop at `last`, which the
    // motion can always do. Binding where that is beyond what the plan found final. Never `last` itself:
    // its speed is the assumed stop, and two rests in a row would cross the path between them in no time.
    // (A quarter, not more: every sample handed on this way brakes for the assumed stop, and the next
    // window speeds up again.)
    const double quarter_s = window_.s[first_waiting_] + 0.25 * (window_.s[last] - window_.s[first_waiting_]);
    const auto after = std::upper_bound(window_.s.begin() + static_cast<std::ptrdiff_t>(first_waiting_),
                                        window_.s.begin() + static_cast<std::ptrdiff_t>(last), quarter_s);
    const std::size_t quarter =
        std::max(first_waiting_, static_cast<std::size_t>(after - window_.s.begin()) - 1);
    if (!found || quarter > final_sample) {
      ++binding_count_;
      final_sample = quarter;
    }
  } else if (!found) {
    return;  // wait for more path: its braking distance may be there
  }
  hand_on(final_sample);
  full_window_step_ = std::max<std::size_t>(1, (window_.size() - first_waiting_) / kFullWindowSteps);
  drop_history();
}

long plan_speeds_lookahead(ProfileSamples& samples, const std::vector<int>& sample_move,
                           const LookaheadSettings& settings) {
  LookaheadProfile profile(settings);
  std::size_t written = 0;
  auto take = [&] {
    for (const PlannedSample& planned : profile.planned()) {
      samples.speed[written] = planned.speed;
      samples.speed_cap[written] = planned.speed_cap;
      samples.accel_cap[written] = planned.accel_cap;
      ++written;
    }
    profile.clear_planned();
  };
  for (std::size_t i = 0; i < samples.size(); ++i) {
    profile.push(RawSample{samples.s[i], samples.speed_cap[i], samples.accel_cap[i], samples.hold_s[i],
                           samples.stop[i] != 0, sample_move[i]});
    take();
  }
  profile.finish();
  take();
  return profile.binding_count();
}

}  // namespace pkm::planning
