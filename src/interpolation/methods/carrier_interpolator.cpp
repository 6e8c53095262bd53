#include "interpolation/methods/carrier_interpolator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pkm::interpolation {

namespace {
constexpr int kCarrierShortenings = 12;        // chord/drive re-checks of one period
constexpr double kCarrierChordReserve = 0.98;  // aim just inside the tolerance: L(s) is not exactly quadratic
}  // namespace

CarrierInterpolator::CarrierInterpolator(const StrutLaws& laws, const IdealTiming& timing,
                                         const CarrierSettings& settings)
    : laws_(laws),
      timing_(timing),
      settings_(settings),
      override_(settings.feed_override, settings.period_s),
      count_(laws.actuator_count()) {
  statistics_.ideal_time_s = timing.duration_s();
}

bool CarrierInterpolator::evaluate(double s, std::array<double, kMaxActuators>& values) {
  if (laws_.evaluate(s, hint_, values.data())) return true;
  error_ = Error{ErrorCode::unreachable,
                 fmt::format("line {}: the path leaves the workspace at s = {:.4f}", laws_.line(hint_), s)};
  return false;
}

Status CarrierInterpolator::start(std::array<double, kMaxActuators>& start_values) {
  tau_ = 0.0;
  s_ = timing_.s_at(0.0);
  if (!evaluate(s_, values_)) return *error_;
  start_values = values_;
  return ok_status();
}

bool CarrierInterpolator::next(CarrierPeriod& period) {
  if (done_ || error_) return false;
  const double h = settings_.period_s;
  if (index_ >= settings_.max_periods) {
    error_ = Error{ErrorCode::limit_exceeded, fmt::format("the run needs more than {} periods of {} ms",
                                                          settings_.max_periods, h * 1e3)};
    return false;
  }
  const double factor = override_.factor(index_);
  if (factor <= 0.0 && override_.stalled()) {
    error_ = Error{ErrorCode::bad_input,
                   fmt::format("the feed override stays at 0 % from {:.3f} s on: the run would never end",
                               static_cast<double>(index_) * h)};
    return false;
  }
  const double end_tau = timing_.duration_s();
  period.index = index_;
  period.time_s = static_cast<double>(index_ + 1) * h;
  period.tau_start_s = tau_;
  period.s_start = s_;
  period.start = values_;
  period.override_factor = factor;
  period.reduced_by_chord = false;
  period.reduced_by_drives = false;

  double delta_tau = factor * h;
  std::array<double, kMaxActuators> middle{};
  for (int attempt = 0;; ++attempt) {
    double tau_end = std::min(tau_ + delta_tau, end_tau);
    if (end_tau - tau_end <= 1e-9 * h) tau_end = end_tau;  // round-off of Σ h must not add a sliver period
    period.last = tau_end >= end_tau;
    period.tau_end_s = tau_end;
    period.s_end = period.last ? timing_.length() : timing_.s_at(tau_end);
    const double s_mid = 0.5 * (s_ + period.s_end);
    if (!evaluate(s_mid, middle) || !evaluate(period.s_end, period.target)) return false;
    double chord = 0.0;
    double scale = 1.0;
    for (int j = 0; j < count_; ++j) {
      // eq. 154: the law at mid-period against the chord of the drive's constant speed.
      chord = std::max(chord, std::abs(middle[j] - 0.5 * (values_[j] + period.target[j])));
      const double increment = std::abs(period.target[j] - values_[j]);
      const double allowed = settings_.max_increment[j];
      if (allowed > 0.0 && increment > allowed) {
        scale = std::min(scale, 0.999 * allowed / increment);
        period.reduced_by_drives = true;
      }
    }
    period.chord_error = chord;
    if (settings_.chord_check && chord > settings_.strut_tolerance) {
      // eq. 159: the chord error is quadratic in the piece's length. Where that did not hold twice (a
      // corner of the path inside the piece, where the law kinks, makes it linear), shorten linearly.
      const double ratio = settings_.strut_tolerance / chord;
      scale = std::min(scale, kCarrierChordReserve * (attempt < 2 ? std::sqrt(ratio) : ratio));
      period.reduced_by_chord = true;
    }
    if (scale >= 1.0 || attempt == kCarrierShortenings) break;
    delta_tau *= scale;
  }
  statistics_.max_chord_error = std::max(statistics_.max_chord_error, period.chord_error);
  if (period.reduced_by_chord) ++statistics_.chord_reduced_periods;
  if (period.reduced_by_drives) ++statistics_.drive_reduced_periods;
  period.hint = hint_;
  tau_ = period.tau_end_s;
  s_ = period.s_end;
  values_ = period.target;
  done_ = period.last;
  if (done_) statistics_.ideal_time_s = timing_.duration_s();  // a timing window knows it only now
  ++index_;
  statistics_.periods = index_;
  statistics_.real_time_s = static_cast<double>(index_) * h;
  return true;
}

}  // namespace pkm::interpolation
