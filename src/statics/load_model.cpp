#include "statics/load_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>

namespace pkm::statics {

bool CuttingLoad::is_zero() const {
  return tangential_N == 0.0 && normal_N == 0.0 && axial_N == 0.0 && force_N.isZero(0.0) &&
         moment_Nmm.isZero(0.0);
}

const CuttingLoad& LoadModel::load_for_line(int line) const {
  if (blocks_ascending) {
    const auto after = std::upper_bound(blocks.begin(), blocks.end(), line,
                                        [](int l, const BlockLoad& b) { return l < b.first_line; });
    if (after == blocks.begin()) return default_load;
    const BlockLoad& block = *(after - 1);
    return line <= block.last_line ? block.load : default_load;
  }
  for (auto it = blocks.rbegin(); it != blocks.rend(); ++it) {
    if (it->first_line <= line && line <= it->last_line) return it->load;
  }
  return default_load;
}

LoadPoint travel_load_point(const Pose& pose, const Eigen::Vector3d& velocity_mm_s,
                            const Eigen::Vector3d& tool_axis_platform, int line, bool cutting) {
  LoadPoint point;
  const double speed = velocity_mm_s.norm();
  point.tangent = speed > 0.0 ? Eigen::Vector3d(velocity_mm_s / speed) : Eigen::Vector3d::Zero();
  point.tool_axis = pose.rotation * tool_axis_platform;
  point.line = line;
  point.cutting = cutting;
  return point;
}

Wrench LoadModel::wrench_at(const LoadPoint& point) const {
  return cutting_wrench(load_for_line(point.line), point);
}

bool LoadModel::empty() const {
  if (!default_load.is_zero()) return false;
  for (const BlockLoad& b : blocks) {
    if (!b.load.is_zero()) return false;
  }
  return true;
}

Wrench cutting_wrench(const CuttingLoad& load, const LoadPoint& point) {
  Wrench w{load.force_N, load.moment_Nmm};
  const double speed = point.tangent.norm();
  // A point that does not move, or a rapid, cuts nothing: only the constant load acts.
  if (!point.cutting || !(speed > 0.0)) return w;
  const Eigen::Vector3d t = point.tangent / speed;
  const Eigen::Vector3d a = point.tool_axis.normalized();
  const Eigen::Vector3d tangential = -load.tangential_N * t;  // Smirnov's P_τ, against the feed (§3.1)
  w.force_N += tangential + load.axial_N * a;
  const Eigen::Vector3d side = a.cross(t);
  const double side_norm = side.norm();
  // Travel along the tool axis (a plunge): no side to the left or right of it.
  if (!(side_norm > 1e-12)) return w;
  const Eigen::Vector3d n = side / side_norm;
  w.force_N += load.normal_N * n;
  // §3.4.2: the tangential force acts at the cutter edge, R_Ф from the tool point on the contact side.
  const Eigen::Vector3d contact = load.cutter_radius_mm * load.contact_side * n;
  w.moment_Nmm += contact.cross(tangential);
  return w;
}

}  // namespace pkm::statics
