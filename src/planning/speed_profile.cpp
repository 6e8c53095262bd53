#include "planning/speed_profile.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace pkm::planning {

void ProfileSamples::resize(std::size_t n) {
  s.resize(n);
  speed_cap.resize(n);
  accel_cap.resize(n);
  speed.resize(n);
  hold_s.resize(n);
  stop.resize(n);
}

void ProfileSamples::erase_front(std::size_t count) {
  const auto erase = [count](auto& values) {
    values.erase(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(count));
  };
  erase(s);
  erase(speed_cap);
  erase(accel_cap);
  erase(speed);
  erase(hold_s);
  erase(stop);
  first += count;
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

void erode_caps(ProfileSamples& p, double window_s, double margin) {
  const std::size_t n = p.size();
  if (n == 0 || window_s <= 0.0) return;
  // Sample j's cap V_j spreads over [s_j − T·V_j − margin, s_j + T·V_j + margin], one more sample on each
  // side (caps hold at samples, the reach ends between them), and never across a stop.
  std::vector<std::size_t> lo(n), hi(n), previous_stop(n), next_stop(n);
  for (std::size_t i = 0, last = 0; i < n; ++i) previous_stop[i] = last = p.stop[i] ? i : last;
  for (std::size_t i = n, next = n - 1; i-- > 0;) next_stop[i] = next = p.stop[i] ? i : next;
  std::vector<std::size_t> order;
  order.reserve(n);
  for (std::size_t j = 0; j < n; ++j) {
    if (p.stop[j]) continue;  // a stop's zero cap is met by its rest, not by slowing its neighbours
    const double reach = window_s * p.speed_cap[j] + margin;
    std::size_t l =
        static_cast<std::size_t>(std::lower_bound(p.s.begin(), p.s.end(), p.s[j] - reach) - p.s.begin());
    std::size_t h =
        static_cast<std::size_t>(std::upper_bound(p.s.begin(), p.s.end(), p.s[j] + reach) - p.s.begin());
    if (l > 0) --l;
    if (h >= n) h = n - 1;
    lo[j] = std::max(l, previous_stop[j]);
    hi[j] = std::min(h, next_stop[j]);
    order.push_back(j);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo[a] < lo[b]; });
  // Sweep: at sample i the smallest speed and acceleration caps of the spreads that cover it (heaps of
  // (cap, last covered sample), stale tops dropped as the sweep passes them).
  using Spread = std::pair<double, std::size_t>;
  std::priority_queue<Spread, std::vector<Spread>, std::greater<>> speed, accel;
  std::vector<double> speed_cap(n), accel_cap(n);
  std::size_t next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (; next < order.size() && lo[order[next]] <= i; ++next) {
      speed.emplace(p.speed_cap[order[next]], hi[order[next]]);
      accel.emplace(p.accel_cap[order[next]], hi[order[next]]);
    }
    while (!speed.empty() && speed.top().second < i) speed.pop();
    while (!accel.empty() && accel.top().second < i) accel.pop();
    speed_cap[i] =
        p.stop[i] ? 0.0 : (speed.empty() ? p.speed_cap[i] : std::min(p.speed_cap[i], speed.top().first));
    accel_cap[i] = accel.empty() ? p.accel_cap[i] : std::min(p.accel_cap[i], accel.top().first);
  }
  p.speed_cap = std::move(speed_cap);
  p.accel_cap = std::move(accel_cap);
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
  const std::size_t first = samples_.first;
  const std::size_t n = samples_.size();
  if (n == 0) return 0.0;
  // Advance to the last sample whose departure is at or before t.
  std::size_t i = std::max(index_, first) - first;
  while (i + 1 < n && timed_.time_s[i + 1] <= t_s) ++i;
  index_ = first + i;
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
