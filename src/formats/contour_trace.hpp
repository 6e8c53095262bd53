#pragma once
// DIR/contour.csv of `pkm interpolate`: per servo period, what the drives' whole steps did to the tool — the
// largest contour error in the period, where FK puts the tool at its end and where the programmed path is
// then (base frame, mm). The report (report/interpolate_report.cpp) draws the executed path and its error
// from it; steps.csv stays the drives' own record. Staged like the other outputs: no file unless the run
// succeeds.
#include <Eigen/Core>
#include <string>

#include "interpolation/contour/contour_monitor.hpp"
#include "interpolation/quantisation/step_period.hpp"
#include "io/atomic_file.hpp"

namespace pkm::formats {

class ContourTraceWriter {
 public:
  Status open(const std::string& path);
  /// One row; buffered, no allocation per period once the buffer has grown.
  Status add(const interpolation::StepPeriod& period, const interpolation::PeriodContour& contour,
             const Eigen::Vector3d& path_mm);
  Status finish();

 private:
  Status flush();

  StagedFile file_;
  std::string buffer_;
  bool open_ = false;
};

}  // namespace pkm::formats
