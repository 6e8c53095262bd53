#include "interpolation/methods/feed_override.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pkm::interpolation {

Result<std::vector<OverrideChange>> parse_override_changes(const std::string& text) {
  std::vector<OverrideChange> changes;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto colon = item.find(':');
    OverrideChange change;
    std::size_t used_time = 0;
    std::size_t used_pct = 0;
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      change.time_s = std::stod(item.substr(0, colon), &used_time);
      change.percent = std::stod(item.substr(colon + 1), &used_pct);
    } catch (const std::exception&) {
      used_time = 0;
    }
    if (colon == std::string::npos || used_time != colon || used_pct != item.size() - colon - 1 ||
        !(change.time_s >= 0.0) || !(change.percent >= 0.0 && change.percent <= 200.0)) {
      return Error{
          ErrorCode::bad_input,
          fmt::format("override change '{}' is not TIME_S:PERCENT with time ≥ 0 s and 0…200 %", item)};
    }
    if (!changes.empty() && change.time_s < changes.back().time_s) {
      return Error{
          ErrorCode::bad_input,
          fmt::format("override change '{}' comes before the previous change; give them in time order",
                      item)};
    }
    changes.push_back(change);
  }
  return changes;
}

FeedOverride::FeedOverride(const OverrideSettings& settings, double period_s)
    : settings_(settings), period_s_(period_s) {
  from_ = to_ = current_ = settings.initial_percent / 100.0;
}

double FeedOverride::factor(long index) noexcept {
  // Changes made during period i (t_H^i ≤ t < t_H^{i+1}) start their transition at origin i+1.
  while (next_change_ < settings_.changes.size()) {
    const OverrideChange& change = settings_.changes[next_change_];
    const long made_in = static_cast<long>(std::floor(change.time_s / period_s_ + 1e-9));
    if (made_in + 2 > index) break;
    from_ = current_;
    to_ = change.percent / 100.0;
    origin_ = made_in + 1;
    ++next_change_;
  }
  if (origin_ >= 0 && current_ != to_) {
    const double span_s = std::abs(to_ - from_) * settings_.full_ramp_s *
                          (settings_.shape == RampShape::s_curve ? 1.5 : 1.0);  // same peak acceleration
    const double elapsed_s = static_cast<double>(index - origin_) * period_s_;
    double u = span_s > 0.0 ? std::clamp(elapsed_s / span_s, 0.0, 1.0) : 1.0;
    if (settings_.shape == RampShape::s_curve) u = u * u * (3.0 - 2.0 * u);
    current_ = u >= 1.0 ? to_ : from_ + (to_ - from_) * u;
  }
  return current_;
}

bool FeedOverride::stalled() const noexcept {
  return current_ <= 0.0 && to_ <= 0.0 && next_change_ >= settings_.changes.size();
}

}  // namespace pkm::interpolation
