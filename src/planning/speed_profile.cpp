#include "planning/speed_profile.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace pkm::planning {

void ProfileSamples::resize(std::size_t n) {
  s.resize(n);
  speed_cap.resize(n);
  accel_cap.resize(n);
  speed.resize(n);
  hold_s.resize(n);
  stop.resize(n);
}

void plan_speeds(ProfileSamples& p) {
  const std::size_t n = p.size();
  if (n == 0) return;
  p.speed[0] = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const double a = std::min(p.accel_cap[i - 1], p.accel_cap[i]);
    const double reachable = std::sqrt(p.speed[i - 1] * p.speed[i - 1] + 2.0 * a * (p.s[i] - p.s[i - 1]));
    p.speed[i] = std::min(p.speed_cap[i], reachable);
  }
  p.speed[n - 1] = 0.0;
  for (std::size_t i = n - 1; i-- > 0;) {
    const double a = std::min(p.accel_cap[i], p.accel_cap[i + 1]);
    const double brakeable = std::sqrt(p.speed[i + 1] * p.speed[i + 1] + 2.0 * a * (p.s[i + 1] - p.s[i]));
    p.speed[i] = std::min(p.speed[i], brakeable);
  }
}

namespace {

/// Sliding-window minimum over windows [lo_i, hi_i] of sample indices, both non-decreasing in i.
std::vector<double> window_minimum(const std::vector<double>& values, const std::vector<std::size_t>& lo,
                                   const std::vector<std::size_t>& hi) {
  const std::size_t n = values.size();
  std::vector<double> out(n);
  std::deque<std::size_t> window;  // indices with increasing values
  std::size_t next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (next <= hi[i] && next < n) {
      while (!window.empty() && values[window.back()] >= values[next]) window.pop_back();
      window.push_back(next++);
    }
    while (window.front() < lo[i]) window.pop_front();
    out[i] = values[window.front()];
  }
  return out;
}

}  // namespace

void erode_caps(ProfileSamples& p, double window_s, double accel_max, double margin) {
  const std::size_t n = p.size();
  if (n == 0 || window_s <= 0.0) return;
  // Reach of the window around sample i, as index ranges made monotone by widening (conservative).
  std::vector<std::size_t> lo(n), hi(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Within one window the speed differs from v_i by at most a·T, so the window spans at most
    // T·v_i + a·T²/2 of path on either side of s_i.
    const double reach = window_s * p.speed[i] + 0.5 * accel_max * window_s * window_s + margin;
    lo[i] = static_cast<std::size_t>(std::lower_bound(p.s.begin(), p.s.end(), p.s[i] - reach) - p.s.begin());
    hi[i] = static_cast<std::size_t>(std::upper_bound(p.s.begin(), p.s.end(), p.s[i] + reach) - p.s.begin());
    // One more sample on each side: caps hold at samples, the window's ends fall between them.
    if (lo[i] > 0) --lo[i];
    if (hi[i] >= n) hi[i] = n - 1;
  }
  for (std::size_t i = n - 1; i-- > 0;) lo[i] = std::min(lo[i], lo[i + 1]);
  for (std::size_t i = 1; i < n; ++i) hi[i] = std::max(hi[i], hi[i - 1]);
  // Clip at the stops around each sample (both bounds stay non-decreasing).
  std::size_t last_stop = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (p.stop[i]) last_stop = i;
    lo[i] = std::max(lo[i], last_stop);
  }
  std::size_t next_stop = n - 1;
  for (std::size_t i = n; i-- > 0;) {
    if (p.stop[i]) next_stop = i;
    hi[i] = std::min(hi[i], next_stop);
  }
  std::vector<double> caps = p.speed_cap;
  for (std::size_t i = 0; i < n; ++i) {
    if (p.stop[i]) caps[i] = std::numeric_limits<double>::infinity();
  }
  p.speed_cap = window_minimum(caps, lo, hi);
  for (std::size_t i = 0; i < n; ++i) {
    if (p.stop[i]) p.speed_cap[i] = 0.0;
  }
  p.accel_cap = window_minimum(p.accel_cap, lo, hi);
}

TimedProfile time_profile(const ProfileSamples& p) {
  TimedProfile timed;
  const std::size_t n = p.size();
  timed.time_s.resize(n);
  double t = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    timed.time_s[i] = t;
    t += p.hold_s[i];
    if (i + 1 < n) {
      const double v_sum = p.speed[i] + p.speed[i + 1];
      if (v_sum > 0.0) t += 2.0 * (p.s[i + 1] - p.s[i]) / v_sum;
    }
  }
  timed.end_time_s = t;
  return timed;
}

double ProfileCursor::position_at(double t_s) {
  const std::size_t n = samples_.size();
  if (n == 0) return 0.0;
  // Advance to the last sample whose departure is at or before t.
  while (index_ + 1 < n && timed_.time_s[index_ + 1] <= t_s) ++index_;
  const std::size_t i = index_;
  const double depart = timed_.time_s[i] + samples_.hold_s[i];
  if (i + 1 >= n || t_s <= depart) return samples_.s[i];
  const double ds = samples_.s[i + 1] - samples_.s[i];
  const double v0 = samples_.speed[i], v1 = samples_.speed[i + 1];
  const double duration = timed_.time_s[i + 1] - depart;
  const double tau = std::min(t_s - depart, duration);
  const double accel = duration > 0.0 ? (v1 - v0) / duration : 0.0;
  return std::min(samples_.s[i] + v0 * tau + 0.5 * accel * tau * tau, samples_.s[i] + ds);
}

}  // namespace pkm::planning
