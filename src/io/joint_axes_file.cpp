// The neutral axes of the passive joints (`base_joint_axes`, `platform_joint_axes`), by default the strut
// directions at home: real machines mount their joints centred at the home pose, so that the swing is
// shared evenly over the workspace around it.
#include <fmt/format.h>

#include <cmath>

#include "io/machine_file_sections.hpp"

namespace pkm {
namespace {

// A base-frame direction at home in the frame of the joint's mount (turned back by the carriage's yaw).
Eigen::Vector3d to_mount_frame(const StrutJointPoints& home, int j, const Eigen::Vector3d& direction) {
  if (!home.mounts_turn) return direction;
  const double c = std::cos(home.mount_yaw_rad[j]), s = std::sin(home.mount_yaw_rad[j]);
  return {c * direction.x() + s * direction.y(), -s * direction.x() + c * direction.y(), direction.z()};
}

// Unit axes from the file, one per strut.
Result<std::array<Eigen::Vector3d, kMaxActuators>> read_axes(const YAML::Node& root, const YamlReader& reader,
                                                             const char* key, int count) {
  auto points = reader.points(root, key, count, 3);
  if (!points) return points.error();
  std::array<Eigen::Vector3d, kMaxActuators> out;
  for (int j = 0; j < count; ++j) {
    const double norm = (*points)[j].norm();
    if (!(norm > 0.0)) {
      return reader.error_at(root[key][j], fmt::format("{}[{}]", key, j), "a direction must not be zero");
    }
    out[j] = (*points)[j] / norm;
  }
  return out;
}

}  // namespace

Result<PassiveJointAxes> read_passive_joint_axes(const YAML::Node& root, const YamlReader& reader,
                                                 const Mechanism& mechanism) {
  PassiveJointAxes axes;
  StrutJointPoints home;
  const int count = mechanism.strut_joints(mechanism.home(), home);
  for (const char* key : {"base_joint_axes", "platform_joint_axes"}) {
    if (root[key] && count == 0) {
      return reader.error_at(root[key], key, "this mechanism has no passive swing joints; remove this key");
    }
  }
  if (count < 0) {
    return reader.error_at(root["home"] ? root["home"] : root["type"], "home",
                           "the home pose is out of reach, so its joint angles are undefined");
  }
  axes.count = count;
  for (int j = 0; j < count; ++j) {
    const Eigen::Vector3d strut = home.platform_mm[j] - home.base_mm[j];
    const double length = strut.norm();
    if (!(length > 0.0)) {
      return reader.error_at(root["home"] ? root["home"] : root["type"], "home",
                             fmt::format("strut {} has zero length at the home pose", j + 1));
    }
    const Eigen::Vector3d direction = strut / length;
    axes.base[j] = to_mount_frame(home, j, direction);
    axes.platform[j] = home.platform_rotation.transpose() * direction;
  }
  if (root["base_joint_axes"]) {
    auto given = read_axes(root, reader, "base_joint_axes", count);
    if (!given) return given.error();
    for (int j = 0; j < count; ++j) axes.base[j] = to_mount_frame(home, j, (*given)[j]);
    axes.base_line = yaml_key_line(root, "base_joint_axes");
  }
  if (root["platform_joint_axes"]) {
    auto given = read_axes(root, reader, "platform_joint_axes", count);
    if (!given) return given.error();
    axes.platform = *given;
    axes.platform_line = yaml_key_line(root, "platform_joint_axes");
  }
  return axes;
}

}  // namespace pkm
