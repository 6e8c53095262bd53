#include "report/scene.hpp"

#include <algorithm>
#include <cmath>

#include "core/units.hpp"
#include "report/decimator.hpp"

namespace pkm::report {

namespace {

/// The struts to draw at `pose`: both ends of every strut (Mechanism::strut_ends: the passive joints, or the
/// planar mechanisms' pins in z = 0).
int drawn_struts(const Mechanism& mechanism, const Pose& pose, StrutJointPoints& joints) {
  return mechanism.strut_ends(pose, joints);
}

nlohmann::json point_json(const Eigen::Vector3d& p) {
  // 0.1 µm is far below anything the view can show; fewer digits keep the page small.
  return nlohmann::json::array(
      {std::round(p.x() * 1e4) / 1e4, std::round(p.y() * 1e4) / 1e4, std::round(p.z() * 1e4) / 1e4});
}

/// The base joints at home, ordered round their centroid: the base outline.
nlohmann::json base_outline(const Machine& machine) {
  StrutJointPoints joints;
  const int n = drawn_struts(*machine.mechanism, machine.mechanism->home(), joints);
  nlohmann::json outline = nlohmann::json::array();
  if (n <= 0) return outline;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int j = 0; j < n; ++j) centre += joints.base_mm[j];
  centre /= n;
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) order[static_cast<std::size_t>(j)] = j;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Eigen::Vector3d da = joints.base_mm[a] - centre, db = joints.base_mm[b] - centre;
    return std::atan2(da.y(), da.x()) < std::atan2(db.y(), db.x());
  });
  Eigen::Vector3d previous(std::nan(""), 0, 0);
  for (int j : order) {
    // Merged joints (a 6-3 layout) are one corner of the outline.
    if ((joints.base_mm[j] - previous).norm() < 1e-6) continue;
    outline.push_back(point_json(joints.base_mm[j]));
    previous = joints.base_mm[j];
  }
  return outline;
}

}  // namespace

ActuatorLimits limits_in_file_units(const Machine& machine) {
  ActuatorLimits limits = machine.limits;
  if (machine.mechanism->actuators_are_angles()) {
    for (std::optional<double>* value : {&limits.min, &limits.max, &limits.speed, &limits.accel}) {
      if (*value) **value = deg_from_rad(**value);
    }
  }
  return limits;
}

double limit_closeness(const ActuatorLimits& limits, double position, double speed, double accel) {
  double closeness = 0.0;
  if (limits.min && limits.max && *limits.max > *limits.min) {
    const double margin = 0.1 * (*limits.max - *limits.min);
    const double room = std::min(position - *limits.min, *limits.max - position);
    closeness = std::max(closeness, 1.0 - room / margin);
  }
  if (limits.speed && *limits.speed > 0.0 && std::isfinite(speed))
    closeness = std::max(closeness, std::abs(speed) / *limits.speed);
  if (limits.accel && *limits.accel > 0.0 && std::isfinite(accel))
    closeness = std::max(closeness, std::abs(accel) / *limits.accel);
  return std::clamp(closeness, 0.0, 1.0);
}

SceneBuilder::SceneBuilder(const Machine& machine, double duration_s, long expected_points, int frames,
                           int path_points)
    : machine_(machine),
      frame_interval_s_(duration_s > 0.0 ? duration_s / frames : 0.0),
      path_bucket_size_(std::max(1L, (expected_points + path_points - 1) / path_points)) {}

void SceneBuilder::add_frame(double time_s, int line, const Pose& pose,
                             const std::vector<double>& closeness) {
  ++frames_;
  next_frame_s_ = time_s + frame_interval_s_;
  lines_.insert(line);
  frame_time_.push_back(json_number(time_s, 9));
  frame_line_.push_back(line);
  frame_tool_.push_back(point_json(pose.position_mm));
  frame_axis_.push_back(point_json(pose.rotation.col(2)));
  StrutJointPoints joints;
  const int n = drawn_struts(*machine_.mechanism, pose, joints);
  nlohmann::json struts = nlohmann::json::array();
  for (int j = 0; j < n; ++j)
    struts.push_back(
        nlohmann::json::array({point_json(joints.base_mm[j]), point_json(joints.platform_mm[j])}));
  frame_struts_.push_back(std::move(struts));
  nlohmann::json near = nlohmann::json::array();
  for (double c : closeness) near.push_back(std::round(c * 1000.0) / 1000.0);
  frame_closeness_.push_back(std::move(near));
}

void SceneBuilder::add_frame_forces(const std::vector<double>& force) {
  nlohmann::json row = nlohmann::json::array();
  // Four digits tell a colour apart far better than the eye can; more would only grow the page.
  for (double f : force) row.push_back(json_number(f, 4));
  frame_force_.push_back(std::move(row));
}

void SceneBuilder::add_path_point(const Eigen::Vector3d& programmed_mm, const Eigen::Vector3d& executed_mm,
                                  double error_mm) {
  if (in_path_bucket_ == 0) {
    bucket_programmed_ = programmed_mm;
    bucket_executed_ = executed_mm;
    bucket_error_ = 0.0;
  }
  if (std::isfinite(error_mm)) {
    bucket_error_ = std::max(bucket_error_, error_mm);
    max_error_ = std::max(max_error_, error_mm);
  }
  last_programmed_ = programmed_mm;
  last_executed_ = executed_mm;
  last_error_ = std::isfinite(error_mm) ? error_mm : 0.0;
  if (++in_path_bucket_ == path_bucket_size_) flush_path_bucket();
}

void SceneBuilder::flush_path_bucket() {
  if (in_path_bucket_ == 0) return;
  programmed_.push_back(point_json(bucket_programmed_));
  executed_.push_back(point_json(bucket_executed_));
  // The bucket's worst error colours its point: a short excursion must not vanish in decimation.
  executed_error_.push_back(json_number(bucket_error_, 3));
  in_path_bucket_ = 0;
}

nlohmann::json SceneBuilder::json() {
  flush_path_bucket();
  if (!programmed_.empty()) {  // the path's own end point, exactly
    programmed_.push_back(point_json(last_programmed_));
    executed_.push_back(point_json(last_executed_));
    executed_error_.push_back(json_number(last_error_, 3));
  }
  const double scale = error_scale_mm_ > 0.0 ? error_scale_mm_ : max_error_;
  nlohmann::json scene = {{"base_polygon", base_outline(machine_)},
                          {"programmed_path", programmed_},
                          {"executed_path", executed_},
                          {"executed_error_mm", executed_error_},
                          {"error_scale_mm", json_number(scale > 0.0 ? scale : 1e-3, 3)},
                          {"frames",
                           {{"time_s", frame_time_},
                            {"line", frame_line_},
                            {"tool", frame_tool_},
                            {"tool_axis", frame_axis_},
                            {"struts", frame_struts_},
                            {"strut_closeness", frame_closeness_}}}};
  // Only a run with drive forces at every frame gets them: the page offers force colouring when they exist.
  if (!frame_force_.empty() && frame_force_.size() == frame_time_.size()) {
    scene["frames"]["drive_force"] = frame_force_;
    scene["drive_force_scale"] = json_number(force_scale_ > 0.0 ? force_scale_ : 1.0, 4);
    scene["drive_force_unit"] = force_unit_;
  }
  return scene;
}

}  // namespace pkm::report
