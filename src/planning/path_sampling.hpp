#pragma once
// The planning grid: samples along the path where inverse kinematics is solved, every limit is checked, and
// the speed and acceleration caps of the speed profile come from (speed_profile.hpp).
//
// At each sample the actuator derivatives along the path, q' = dq/ds and q'' = d²q/ds², come from finite
// differences of the inverse kinematics on the grid. With path speed v and tangential acceleration a,
//   q̇ = q'·v,   q̈ = q'·a + q''·v²,
// so the caps are
//   v ≤ margin·q̇_max / |q'_j|,   v ≤ sqrt(α·margin·q̈_max / |q''_j|),   a ≤ (1 − α)·margin·q̈_max / |q'_j|,
// with α = ½ of the acceleration budget reserved for the curvature term. The path's own limits: the
// programmed feed times the override, the path acceleration (also normal: κ·v² ≤ a_path), and the chord error
// between servo periods (textbook eq. 2.3: v ≤ sqrt(8·R·δ)/h, on the tool and on every actuator).
#include <array>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "path/path.hpp"
#include "planning/lookahead_profile.hpp"
#include "planning/motion_plan.hpp"
#include "planning/speed_profile.hpp"

namespace pkm::planning {

struct SamplingSettings {
  double override_factor = 1.0;
  double actuator_margin = 0.95;
  double spacing = 1.0;            ///< largest sample spacing, path units
  double condition_spacing = 2.0;  ///< conditioning checked at least this often, path units
  double period_s = 0.001;
  double stop_hold_s = 0.0;  ///< rest at every stop so that the jerk filter settles there
  double chord_tolerance_mm =
      1e-3;  ///< allowed deviation between servo periods, on the tool and on actuators
  std::size_t max_samples = 50'000'000;  ///< refuse a path that needs more (PlanOptions::max_samples)
  int total_lines = 0;                   ///< the program's lines, for the progress' fraction (0: unknown)
  ProgressSink progress;                 ///< told "planning", the fraction of the lines and the line
};

/// A planning sample with its caps (lookahead_profile.hpp) and the path segment it lies on.
struct SampledPoint {
  RawSample raw;
  int segment = 0;
};

/// The planning grid of a path that grows at its end (path_appender.hpp): the final segments are sampled as
/// they come, a sample's caps are handed on once the sample after it is known, and only the last three
/// samples are kept, so memory does not grow with the path.
class PathSampler {
 public:
  PathSampler(const Machine& machine, std::string source, const path::Path& path,
              const SamplingSettings& settings);
  /// Samples the path's segments up to (not including) `end`. Errors name the program line and the limit.
  Status add_segments(int end);
  /// The path ends at its last segment: the last sample, at rest there.
  Status finish();
  /// Samples whose caps are final, in path order, not yet taken; clear_ready() after reading them.
  const std::vector<SampledPoint>& ready() const { return ready_; }
  void clear_ready() { ready_.clear(); }
  /// Samples placed so far, the largest condition number met, the share of the length the actuators limit.
  std::size_t sample_count() const { return count_; }
  double max_condition_number() const { return max_condition_; }
  double actuator_limited_length() const { return actuator_limited_length_; }
  /// The first path segment the sampler still reads (the ones before it may be dropped).
  int first_needed_segment() const;
  /// The last error was a pose out of reach or past a position limit (not the bound on the samples).
  bool failed_in_workspace() const { return failed_in_workspace_; }

 private:
  struct Point {
    double s = 0.0;
    int segment = 0;
    bool stop = false;
    double hold_s = 0.0;
    bool last = false;
    ActuatorVector q;
    Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  };
  Status place(double s, int segment, bool last);
  Status solve(Point& point);
  void hand_on_caps(bool last);

  const Machine& machine_;
  std::string source_;
  const path::Path& path_;
  SamplingSettings settings_;
  std::array<Point, 3> ring_;  ///< the last three samples, by count % 3
  std::size_t count_ = 0;
  int next_segment_ = 0;
  std::vector<double> fractions_;
  double next_condition_check_ = 0.0;
  double max_condition_ = 0.0;
  double actuator_limited_length_ = 0.0;
  std::vector<SampledPoint> ready_;
  bool failed_in_workspace_ = false;
};

/// The places of segment `k`'s samples (its start, then inside it; its end is the next segment's start), and
/// how many it needs: where a move needs more than `max_count`, nothing is placed (in double: a huge move
/// must be refused, not overflow an int).
double segment_sample_positions(const path::Path& path, int k, double spacing, double max_count,
                                std::vector<double>& out);

/// The samples' places along the whole of `path` (as PathSampler places them), for the scan of the
/// workspace excursions after a refusal. Empty when there would be more than `max_samples`.
void whole_path_samples(const path::Path& path, double spacing, std::size_t max_samples,
                        std::vector<double>& s, std::vector<int>& segment);

/// The speed cap a segment's programmed feed sets (path units per second): the feed (or rapid) times the
/// override, capped by the machine's rapid, feed or angular speed.
double segment_speed_cap(const path::Segment& segment, const MotionSettings& motion, double override_factor);

/// "X.. Y.. Z.. A.. B.. C.." of a machine pose in program coordinates, for messages.
std::string program_pose_text(const Machine& machine, const Pose& pose);

}  // namespace pkm::planning
