#include "interpolation/contour/contour_monitor.hpp"

#include <algorithm>

#include "core/units.hpp"

namespace pkm::interpolation {

ContourMonitor::ContourMonitor(const Machine& machine, const path::Path& path, const ContourGauge& gauge,
                               int samples_inside)
    : machine_(machine),
      path_(path),
      gauge_(gauge),
      samples_inside_(std::max(1, samples_inside)),
      count_(machine.mechanism->actuator_count()),
      tracker_(machine, machine.mechanism->home()) {}

void ContourMonitor::record(double error_mm, double rotation_rad, double time_s, int line, bool period_end) {
  ++statistics_.evaluations;
  sum_squares_ += error_mm * error_mm;
  statistics_.rms_error_mm = std::sqrt(sum_squares_ / static_cast<double>(statistics_.evaluations));
  if (error_mm > statistics_.max_error_mm) {
    statistics_.max_error_mm = error_mm;
    statistics_.max_error_time_s = time_s;
    statistics_.max_error_line = line;
  }
  if (periods_ > 1)
    statistics_.max_error_after_first_mm = std::max(statistics_.max_error_after_first_mm, error_mm);
  if (period_end)
    statistics_.max_period_end_error_mm = std::max(statistics_.max_period_end_error_mm, error_mm);
  statistics_.max_rotation_deg = std::max(statistics_.max_rotation_deg, deg_from_rad(rotation_rad));
}

void ContourMonitor::start(const std::array<double, kMaxActuators>& values, double s_start) {
  previous_ = values;
  Pose pose;
  PoseTracker first(machine_, machine_.mechanism->home());
  if (!first.solve(values.data(), pose)) {
    ++statistics_.fk_failures;
    return;
  }
  tracker_.reset(pose);
  const ContourDeviation deviation = gauge_.measure(pose, s_start, hint_);
  statistics_.start_error_mm = deviation.distance_mm;
  record(deviation.distance_mm, deviation.rotation_rad, 0.0,
         path_.segments.empty() ? 0 : path_.segments[0].line, false);
}

void ContourMonitor::add(const std::array<double, kMaxActuators>& values, double s_start, double s_end,
                         double time_s, double period_s, int line, bool last) {
  ++periods_;
  last_period_ = PeriodContour{};
  std::array<double, kMaxActuators> now{};
  const int points = samples_inside_ + 1;
  for (int k = 1; k <= points; ++k) {
    const double f = static_cast<double>(k) / points;
    for (int j = 0; j < count_; ++j) now[j] = previous_[j] + f * (values[j] - previous_[j]);
    Pose pose;
    if (!tracker_.solve(now.data(), pose)) {
      ++statistics_.fk_failures;
      continue;
    }
    const ContourDeviation deviation = gauge_.measure(pose, s_start + f * (s_end - s_start), hint_);
    record(deviation.distance_mm, deviation.rotation_rad, time_s - (1.0 - f) * period_s, line, k == points);
    last_period_.max_error_mm = std::max(last_period_.max_error_mm, deviation.distance_mm);
    if (k == points) {
      last_period_.tool_mm = pose.position_mm;
      last_period_.solved = true;
    }
    if (last && k == points) {
      statistics_.end_error_mm = gauge_.mask(pose.position_mm - path_.end_point().position_mm).norm();
    }
  }
  previous_ = values;
}

}  // namespace pkm::interpolation
