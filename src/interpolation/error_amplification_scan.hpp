#pragma once
// δρ_max of eq. 146 along a tool path (Smirnov 2019, §5.2.2): the largest error amplification of the machine
// at samples along the path, and the program line where it occurs. Smirnov takes the maximum over a working
// space; the path's own maximum is the tighter bound that is sufficient for a run along it. The scan takes
// the path segment by segment, so a plan made while it streams can be scanned as its segments become final.
#include <string>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "path/path.hpp"

namespace pkm::interpolation {

struct ErrorAmplification {
  double largest = 0.0;  ///< δρ_max
  int line = 0;          ///< program line where it occurs (0: the path's start)
};

class ErrorAmplificationScan {
 public:
  /// Samples `spacing` path units apart (at least the segments' ends). Errors name `source` and the line.
  ErrorAmplificationScan(const Machine& machine, double spacing, std::string source);
  /// Samples segment `index` of `path` (whole-path index).
  Status add_segment(const path::Path& path, int index);
  /// After the last segment: a path without any is measured at its start.
  Status finish(const path::Path& path);
  const ErrorAmplification& result() const { return result_; }

 private:
  Status measure(const path::PathPoint& point, int line);

  const Machine& machine_;
  double spacing_;
  std::string source_;
  int hint_ = 0;
  bool sampled_ = false;
  ErrorAmplification result_;
};

}  // namespace pkm::interpolation
