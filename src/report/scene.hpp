#pragma once
// The report's 3-D view (docs/report-data.md, "scene"): the base outline, animation frames with every strut's
// two joints, the tool and how close each actuator is to its limits, and the programmed and executed tool
// paths, decimated to what a browser draws smoothly. Poses are in the machine's base frame.
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "machine/machine.hpp"

namespace pkm::report {

/// How close one actuator is to its limits, 0 (far) … 1 (at a limit): the largest of its position's nearness
/// to either end of the range (within the last 10 % of it), |speed|/limit and |acceleration|/limit. Values in
/// the machine's file units (mm or deg, per s, per s²); NaN speeds or accelerations are not counted.
double limit_closeness(const ActuatorLimits& file_limits, double position, double speed, double accel);

/// The machine's actuator limits in file units (mm or deg): Machine keeps angles in rad.
ActuatorLimits limits_in_file_units(const Machine& machine);

class SceneBuilder {
 public:
  /// `duration_s` and `expected_points` size the frame interval and the path decimation.
  SceneBuilder(const Machine& machine, double duration_s, long expected_points, int frames = 1500,
               int path_points = 40000);

  /// True when a frame is due at `time_s` (the first call, then every duration/frames).
  bool frame_due(double time_s) const { return frames_ == 0 || time_s >= next_frame_s_; }
  /// A frame at `pose`; `closeness` per actuator (limit_closeness()).
  void add_frame(double time_s, int line, const Pose& pose, const std::vector<double>& closeness);
  /// The drive forces at the frame just added (plans with --dynamics): the 3-D view can colour the struts by
  /// them. Either every frame gets them or none does.
  void add_frame_forces(const std::vector<double>& force);
  /// The force that gets the ends of the force colour scale (the run's peak |force|), and its unit.
  void set_force_scale(double peak_force, const std::string& unit) {
    force_scale_ = peak_force;
    force_unit_ = unit;
  }
  /// One point of the tool path: the programmed point, the executed one, and the contour error there.
  void add_path_point(const Eigen::Vector3d& programmed_mm, const Eigen::Vector3d& executed_mm,
                      double error_mm);
  /// Colour scale of the executed path: this error is the hot end (default: the largest seen).
  void set_error_scale(double error_mm) { error_scale_mm_ = error_mm; }
  /// Every program line a frame refers to (for the source text in the report).
  const std::set<int>& lines() const { return lines_; }
  nlohmann::json json();

 private:
  void flush_path_bucket();

  const Machine& machine_;
  double frame_interval_s_;
  double next_frame_s_ = 0.0;
  long frames_ = 0;
  long path_bucket_size_;
  long in_path_bucket_ = 0;
  Eigen::Vector3d bucket_programmed_, bucket_executed_, last_programmed_, last_executed_;
  double bucket_error_ = 0.0, last_error_ = 0.0, max_error_ = 0.0;
  double error_scale_mm_ = 0.0;
  double force_scale_ = 0.0;
  std::string force_unit_;
  std::set<int> lines_;
  nlohmann::json frame_time_ = nlohmann::json::array(), frame_line_ = nlohmann::json::array(),
                 frame_tool_ = nlohmann::json::array(), frame_axis_ = nlohmann::json::array(),
                 frame_struts_ = nlohmann::json::array(), frame_closeness_ = nlohmann::json::array(),
                 frame_force_ = nlohmann::json::array();
  nlohmann::json programmed_ = nlohmann::json::array(), executed_ = nlohmann::json::array(),
                 executed_error_ = nlohmann::json::array();
};

}  // namespace pkm::report
