#pragma once
// What the drives actually do to the tool (Smirnov 2019, ρ): FK of the actual actuator positions, at every
// period's end and at `samples_inside` evenly spaced instants inside it (the drives move linearly through a
// period; a stepper spreads its n_j steps evenly over h), and the perpendicular distance of the tool from
// the programmed path there (contour_gauge.hpp). The publication evaluated five points per period because the
// worst error is at mid-period (Fig. 197, eq. 153).
#include <array>
#include <cmath>

#include "interpolation/contour/contour_gauge.hpp"
#include "interpolation/pose_tracker.hpp"

namespace pkm::interpolation {

struct ContourStatistics {
  double start_error_mm = 0.0;            ///< at the start positions, before the first period
  double max_error_mm = 0.0;              ///< over every evaluated instant
  double max_error_after_first_mm = 0.0;  ///< once the first period has run
  double max_period_end_error_mm = 0.0;
  double rms_error_mm = 0.0;
  double max_rotation_deg = 0.0;  ///< orientation deviation, where the mechanism controls it
  double end_error_mm = 0.0;      ///< distance of the final tool point from the path's end point
  double max_error_time_s = 0.0;
  int max_error_line = 0;
  long evaluations = 0;
  long fk_failures = 0;
};

/// What the last period did (for traces and reports): its largest error and where the tool ended.
struct PeriodContour {
  double max_error_mm = 0.0;                          ///< over the period's evaluated instants
  Eigen::Vector3d tool_mm = Eigen::Vector3d::Zero();  ///< FK of the positions at the period's end, base frame
  bool solved = false;                                ///< false if FK failed at the period's end
};

class ContourMonitor {
 public:
  ContourMonitor(const Machine& machine, const path::Path& path, const ContourGauge& gauge,
                 int samples_inside);
  /// The start positions (actuator values) at path parameter s_start.
  void start(const std::array<double, kMaxActuators>& values, double s_start);
  /// One period from the previous positions to `values`, whose ideal path piece is [s_start, s_end].
  void add(const std::array<double, kMaxActuators>& values, double s_start, double s_end, double time_s,
           double period_s, int line, bool last);
  const ContourStatistics& statistics() const { return statistics_; }
  long fk_solves() const { return tracker_.solves(); }
  const PeriodContour& last_period() const { return last_period_; }

 private:
  void record(double error_mm, double rotation_rad, double time_s, int line, bool period_end);

  const Machine& machine_;
  const path::Path& path_;
  const ContourGauge& gauge_;
  int samples_inside_;
  int count_;
  PoseTracker tracker_;
  std::array<double, kMaxActuators> previous_{};
  double sum_squares_ = 0.0;
  long periods_ = 0;
  int hint_ = 0;
  ContourStatistics statistics_;
  PeriodContour last_period_;
};

}  // namespace pkm::interpolation
