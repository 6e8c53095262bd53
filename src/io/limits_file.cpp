// The `limits:` section: actuator range, speed, acceleration and force; passive-joint swing limits; the
// largest condition number of the Jacobian.
#include <fmt/format.h>

#include "core/units.hpp"
#include "io/machine_file_sections.hpp"

namespace pkm {
namespace {

struct Field {
  const char* key;
  std::optional<double>* value;
  int* line;
};

// Every key is read with its full name ("limits.KEY") so that a message points into the right section.
Status read_fields(const YAML::Node& node, const YamlReader& reader, std::initializer_list<Field> fields) {
  for (const Field& f : fields) {
    const YAML::Node value = node[f.key];
    if (!value) continue;
    auto v = reader.number(value, fmt::format("limits.{}", f.key));
    if (!v) return v.error();
    *f.value = *v;
    *f.line = yaml_line(value);
  }
  return ok_status();
}

Result<ActuatorLimits> read_actuator_limits(const YAML::Node& node, const YamlReader& reader) {
  ActuatorLimits limits;
  if (auto read = read_fields(node, reader,
                              {Field{"actuator_min", &limits.min, &limits.min_line},
                               Field{"actuator_max", &limits.max, &limits.max_line},
                               Field{"actuator_speed", &limits.speed, &limits.speed_line},
                               Field{"actuator_accel", &limits.accel, &limits.accel_line},
                               Field{"actuator_force_max", &limits.force_N, &limits.force_line}});
      !read) {
    return read.error();
  }
  if (limits.min && limits.max && *limits.min >= *limits.max) {
    return reader.error_at(
        node["actuator_max"], "limits.actuator_max",
        fmt::format("must be greater than actuator_min ({} >= {})", *limits.min, *limits.max));
  }
  for (auto [key, value] :
       {std::pair{"actuator_speed", limits.speed}, std::pair{"actuator_accel", limits.accel},
        std::pair{"actuator_force_max", limits.force_N}}) {
    if (value && !(*value > 0.0)) {
      return reader.error_at(node[key], fmt::format("limits.{}", key), "must be positive");
    }
  }
  return limits;
}

Result<JointLimits> read_joint_limits(const YAML::Node& node, const YamlReader& reader, bool planar) {
  JointLimits limits;
  std::optional<double> base_deg, platform_deg;
  if (auto read = read_fields(
          node, reader,
          {Field{"base_joint_max_deg", &base_deg, &limits.base_joint_max_line},
           Field{"platform_joint_max_deg", &platform_deg, &limits.platform_joint_max_line},
           Field{"max_condition_number", &limits.max_condition_number, &limits.max_condition_number_line}});
      !read) {
    return read.error();
  }
  for (auto [key, value] :
       {std::pair{"base_joint_max_deg", base_deg}, std::pair{"platform_joint_max_deg", platform_deg}}) {
    if (!value) continue;
    if (planar) {
      return reader.error_at(node[key], fmt::format("limits.{}", key),
                             "planar mechanisms have pin joints, which have no swing limit; remove this key");
    }
    // A swing is an angle between two directions: 0 to 180 degrees.
    if (!(*value > 0.0 && *value <= 180.0)) {
      return reader.error_at(node[key], fmt::format("limits.{}", key),
                             fmt::format("must be in (0, 180] degrees, got {}", *value));
    }
  }
  if (limits.max_condition_number && !(*limits.max_condition_number >= 1.0)) {
    return reader.error_at(
        node["max_condition_number"], "limits.max_condition_number",
        fmt::format("must be at least 1 (σ_max/σ_min >= 1), got {}", *limits.max_condition_number));
  }
  if (base_deg) limits.base_joint_max_rad = rad_from_deg(*base_deg);
  if (platform_deg) limits.platform_joint_max_rad = rad_from_deg(*platform_deg);
  limits.update_cosines();
  return limits;
}

}  // namespace

Result<FileLimits> read_limits(const YAML::Node& root, const YamlReader& reader, bool planar) {
  FileLimits out;
  const YAML::Node node = root["limits"];
  if (!node) return out;
  if (auto keys = reader.check_keys(
          node, "limits",
          {"actuator_min", "actuator_max", "actuator_speed", "actuator_accel", "actuator_force_max",
           "base_joint_max_deg", "platform_joint_max_deg", "max_condition_number"});
      !keys) {
    return keys.error();
  }
  auto actuators = read_actuator_limits(node, reader);
  if (!actuators) return actuators.error();
  auto joints = read_joint_limits(node, reader, planar);
  if (!joints) return joints.error();
  out.actuators = *actuators;
  out.joints = *joints;
  return out;
}

}  // namespace pkm
