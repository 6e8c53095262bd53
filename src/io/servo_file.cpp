// The `servo:` section: the drives' current loops, base speed and force, motor inertia and transmission,
// clamps, and how the speed and position loops are tuned (machine/servo_parameters.hpp;
// docs/machine-file.md). The unit keys name the actuators' kind: mm, mm/s, N and a screw's lead for struts
// and carriages; deg, deg/s, N·mm and a gear ratio for a rotopod's carriage angles. The other kind's key is
// an error that names the key to give, so a value cannot be read in the wrong unit.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/units.hpp"
#include "io/machine_file_sections.hpp"

namespace pkm {
namespace {

enum class ServoFileBound { positive, non_negative, fraction };

// The most loop periods between sampling and acting (servo/loop_design.hpp's kMaxSampleDelay).
constexpr double kServoFileMaxDelay = 8;

// The keys whose unit depends on the actuators' kind, in the same order for both kinds.
struct ServoFileUnitKeys {
  const char* speed;
  const char* force;
  const char* transmission;
  const char* error_max;
  std::array<const char*, 4> all() const { return {speed, force, transmission, error_max}; }
};
constexpr ServoFileUnitKeys kServoFileLinearKeys{"base_speed_mm_s", "base_force_N", "screw_lead_mm",
                                                 "error_max_mm"};
constexpr ServoFileUnitKeys kServoFileAngularKeys{"base_speed_deg_s", "base_torque_Nmm", "gear_ratio",
                                                  "error_max_deg"};

// The imperfections' keys (machine/servo_parameters.hpp), whose unit depends on the actuators' kind too.
struct ServoFileImperfectionKeys {
  const char* coulomb;
  const char* static_friction;
  const char* stribeck_speed;
  const char* viscous;
  const char* backlash;
  const char* encoder;
  const char* transmission_stiffness;
  const char* transmission_damping;
  std::array<const char*, 8> all() const {
    return {coulomb,  static_friction, stribeck_speed,         viscous,
            backlash, encoder,         transmission_stiffness, transmission_damping};
  }
};
constexpr ServoFileImperfectionKeys kServoFileLinearImperfections{"friction_coulomb_N",
                                                                  "friction_static_N",
                                                                  "stribeck_speed_mm_s",
                                                                  "friction_viscous_N_s_per_mm",
                                                                  "backlash_mm",
                                                                  "encoder_resolution_mm",
                                                                  "transmission_stiffness_N_mm",
                                                                  "transmission_damping_N_s_per_mm"};
constexpr ServoFileImperfectionKeys kServoFileAngularImperfections{"friction_coulomb_Nmm",
                                                                   "friction_static_Nmm",
                                                                   "stribeck_speed_deg_s",
                                                                   "friction_viscous_Nmm_s_per_deg",
                                                                   "backlash_deg",
                                                                   "encoder_resolution_deg",
                                                                   "transmission_stiffness_Nmm_per_deg",
                                                                   "transmission_damping_Nmm_s_per_deg"};

// What every drive's mapping is read with.
struct ServoFileContext {
  const YamlReader& reader;
  const Mechanism& mechanism;
  bool angular;
  ServoTuning tuning;
};

// The error at `key` itself in `parent` (an empty value has no place of its own), `name` in the message.
Error servo_file_error_at_key(const YamlReader& reader, const YAML::Node& parent, const char* key,
                              const std::string& name, const std::string& message) {
  for (const auto& item : parent) {
    if (item.first.IsScalar() && item.first.Scalar() == key)
      return reader.error_at(item.first, name, message);
  }
  return reader.error_at(parent, name, message);
}

// The number under `key` of `parent` when given ("path.key" in messages): finite and within `bound`.
Result<std::optional<double>> servo_file_number(const YamlReader& reader, const YAML::Node& parent,
                                                const std::string& path, const char* key,
                                                ServoFileBound bound) {
  const YAML::Node value = parent[key];
  if (!value) return std::optional<double>{};
  const std::string name = path + "." + key;
  if (value.IsNull())
    return servo_file_error_at_key(reader, parent, key, name, "expected a number, got nothing");
  auto number = reader.number(value, name);
  if (!number) return number.error();
  const double v = *number;
  bool valid = std::isfinite(v);
  const char* must = "positive";
  switch (bound) {
    case ServoFileBound::positive:
      valid = valid && v > 0.0;
      break;
    case ServoFileBound::non_negative:
      valid = valid && v >= 0.0;
      must = "≥ 0";
      break;
    case ServoFileBound::fraction:
      valid = valid && v >= 0.0 && v <= 1.0;
      must = "within 0…1";
      break;
  }
  if (!valid) return reader.error_at(value, name, fmt::format("must be {}, got {}", must, v));
  return std::optional<double>{v};
}

// The same for a key that must be given (`what` says what it is).
Result<double> servo_file_required(const YamlReader& reader, const YAML::Node& parent,
                                   const std::string& path, const char* key, ServoFileBound bound,
                                   const char* what) {
  auto value = servo_file_number(reader, parent, path, key, bound);
  if (!value) return value.error();
  if (!*value) return reader.error_missing(parent, path + "." + key, what);
  return **value;
}

// `tuning:`, when given.
Result<ServoTuning> servo_file_tuning(const YamlReader& reader, const YAML::Node& section) {
  const YAML::Node value = section["tuning"];
  const char* expected = "expected technical_optimum, symmetric_optimum or explicit";
  if (!value.IsScalar()) {
    return servo_file_error_at_key(reader, section, "tuning", "servo.tuning",
                                   fmt::format("{}, got {}", expected,
                                               value.IsNull()       ? "nothing"
                                               : value.IsSequence() ? "a list"
                                                                    : "a mapping"));
  }
  const std::string& name = value.Scalar();
  if (name == "technical_optimum") return ServoTuning::technical_optimum;
  if (name == "symmetric_optimum") return ServoTuning::symmetric_optimum;
  if (name == "explicit") return ServoTuning::explicit_gains;
  return reader.error_at(value, "servo.tuning", fmt::format("{}, got '{}'", expected, name));
}

// The speed and position gains: required with tuning: explicit, refused with the others (they would be
// silently replaced by the tuned ones).
Status servo_file_gains(const ServoFileContext& c, const YAML::Node& node, const std::string& path,
                        DriveServo& drive) {
  if (c.tuning != ServoTuning::explicit_gains) {
    for (const char* key : {"position_gain_per_s", "speed_gain", "speed_integral_ms"}) {
      if (!node[key]) continue;
      return c.reader.error_at(node[key], path + "." + key,
                               fmt::format("only with tuning: explicit (tuning: {} sets the gains from "
                                           "current_time_constant_ms)",
                                           to_string(c.tuning)));
    }
    return ok_status();
  }
  auto position = servo_file_required(c.reader, node, path, "position_gain_per_s", ServoFileBound::positive,
                                      "the position loop's gain, 1/s, with tuning: explicit");
  if (!position) return position.error();
  drive.position_gain_per_s = *position;
  drive.position_gain_line = yaml_key_line(node, "position_gain_per_s");
  auto speed = servo_file_required(c.reader, node, path, "speed_gain", ServoFileBound::positive,
                                   "the speed loop's gain, with tuning: explicit");
  if (!speed) return speed.error();
  drive.speed_gain = *speed;
  drive.speed_gain_line = yaml_key_line(node, "speed_gain");
  auto integral = servo_file_number(c.reader, node, path, "speed_integral_ms", ServoFileBound::non_negative);
  if (!integral) return integral.error();
  drive.speed_integral_s = integral->value_or(0.0) * 1e-3;
  return ok_status();
}

// The drive's imperfections, each ≥ 0 where given; the static friction at least the Coulomb friction, and
// above it with the Stribeck speed over which it falls. Inside, angles in radians.
Status servo_file_imperfections(const ServoFileContext& c, const YAML::Node& node, const std::string& path,
                                DriveServo& drive) {
  const ServoFileImperfectionKeys& keys =
      c.angular ? kServoFileAngularImperfections : kServoFileLinearImperfections;
  const auto keys_all = keys.all();
  std::array<double, 8> values{};
  for (std::size_t i = 0; i < keys_all.size(); ++i) {
    auto value = servo_file_number(c.reader, node, path, keys_all[i], ServoFileBound::non_negative);
    if (!value) return value.error();
    values[i] = value->value_or(0.0);
  }
  const double angle = c.angular ? rad_from_deg(1.0) : 1.0;  // radians per degree, or 1
  drive.friction_coulomb = values[0];
  drive.friction_static = node[keys.static_friction] ? values[1] : values[0];
  drive.stribeck_speed = values[2] * angle;
  drive.friction_viscous = values[3] / angle;  // per deg/s → per rad/s
  drive.backlash = values[4] * angle;
  drive.encoder_resolution = values[5] * angle;
  drive.transmission_stiffness = values[6] / angle;  // per deg → per rad
  drive.transmission_damping = values[7] / angle;
  if (drive.friction_static < drive.friction_coulomb) {
    return c.reader.error_at(node[keys.static_friction], path + "." + keys.static_friction,
                             fmt::format("must be at least {} (the Coulomb friction, {}), got {}",
                                         keys.coulomb, values[0], values[1]));
  }
  if (drive.friction_static > drive.friction_coulomb && !(drive.stribeck_speed > 0.0)) {
    return c.reader.error_missing(node, path + "." + keys.stribeck_speed,
                                  "the Stribeck speed over which the static friction falls to the Coulomb "
                                  "friction (positive), with a static friction above it");
  }
  return ok_status();
}

// `characteristic:`, when given: 2 … 16 points [u, F/F_base] from [0, 0], u rising, F not falling.
Status servo_file_characteristic(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                                 DriveServo& drive) {
  const YAML::Node list = node["characteristic"];
  if (!list) return ok_status();
  const std::string name = path + ".characteristic";
  const int most = DriveServo::kMaxCharacteristicPoints;
  if (!list.IsSequence() || list.size() < 2 || static_cast<int>(list.size()) > most) {
    return reader.error_at(
        list, name,
        fmt::format("expected a list of 2 … {} points [command u, force/F_base] from [0, 0]", most));
  }
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string item = fmt::format("{}[{}]", name, k);
    const YAML::Node point = list[k];
    if (!point.IsSequence() || point.size() != 2)
      return reader.error_at(point, item, "expected a point [command u, force/F_base]");
    for (int i = 0; i < 2; ++i) {
      auto value = reader.number(point[i], item);
      if (!value) return value.error();
      if (!std::isfinite(*value) || *value < 0.0)
        return reader.error_at(point[i], item, fmt::format("must be finite and ≥ 0, got {}", *value));
      drive.characteristic[k][static_cast<std::size_t>(i)] = *value;
    }
    const auto& p = drive.characteristic[k];
    if (k == 0 && (p[0] != 0.0 || p[1] != 0.0))
      return reader.error_at(point, item, "the characteristic starts at [0, 0] (no force without a command)");
    if (k > 0 && !(p[0] > drive.characteristic[k - 1][0]))
      return reader.error_at(point[0], item, "the commands must rise from point to point");
    if (k > 0 && p[1] < drive.characteristic[k - 1][1])
      return reader.error_at(point[1], item, "the force must not fall as the command rises");
  }
  drive.characteristic_points = static_cast<int>(list.size());
  return ok_status();
}

// One drive's mapping (`path`: servo.drives or servo.drives[j]).
Result<DriveServo> servo_file_drive(const ServoFileContext& c, const YAML::Node& node,
                                    const std::string& path) {
  const YamlReader& reader = c.reader;
  if (!node.IsMap()) return reader.error_at(node, path, "expected a mapping (current_time_constant_ms: …)");
  const ServoFileUnitKeys& units = c.angular ? kServoFileAngularKeys : kServoFileLinearKeys;
  const ServoFileUnitKeys& other = c.angular ? kServoFileLinearKeys : kServoFileAngularKeys;
  const ServoFileImperfectionKeys& imperfections =
      c.angular ? kServoFileAngularImperfections : kServoFileLinearImperfections;
  const ServoFileImperfectionKeys& other_imperfections =
      c.angular ? kServoFileLinearImperfections : kServoFileAngularImperfections;
  // The other kind's unit key first: "unknown key" would not say which one to give.
  std::vector<const char*> theirs, ours;
  for (const char* k : other.all()) theirs.push_back(k);
  for (const char* k : other_imperfections.all()) theirs.push_back(k);
  for (const char* k : units.all()) ours.push_back(k);
  for (const char* k : imperfections.all()) ours.push_back(k);
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();  // a scalar: parse_yaml_document checked every key
    for (std::size_t i = 0; i < theirs.size(); ++i) {
      if (key != theirs[i]) continue;
      return reader.error_at(item.first, path + "." + key,
                             fmt::format("the {}'s actuators are {}: give {}", to_string(c.mechanism.type()),
                                         c.angular ? "angles" : "lengths", ours[i]));
    }
  }
  if (auto keys = reader.check_keys(node, path,
                                    {"current_time_constant_ms",
                                     "current_gain",
                                     units.speed,
                                     units.force,
                                     "motor_inertia_kg_cm2",
                                     units.transmission,
                                     units.error_max,
                                     "command_max",
                                     "position_gain_per_s",
                                     "speed_gain",
                                     "speed_integral_ms",
                                     imperfections.coulomb,
                                     imperfections.static_friction,
                                     imperfections.stribeck_speed,
                                     imperfections.viscous,
                                     imperfections.backlash,
                                     imperfections.encoder,
                                     imperfections.transmission_stiffness,
                                     imperfections.transmission_damping,
                                     "characteristic"});
      !keys)
    return keys.error();

  DriveServo drive;
  drive.line = yaml_line(node);
  auto time_constant =
      servo_file_required(reader, node, path, "current_time_constant_ms", ServoFileBound::positive,
                          "the current loop's time constant T_μ, ms");
  if (!time_constant) return time_constant.error();
  drive.current_time_constant_s = *time_constant * 1e-3;
  drive.time_constant_line = yaml_key_line(node, "current_time_constant_ms");
  auto gain = servo_file_number(reader, node, path, "current_gain", ServoFileBound::positive);
  if (!gain) return gain.error();
  drive.current_gain = gain->value_or(1.0);

  auto speed = servo_file_required(reader, node, path, units.speed, ServoFileBound::positive,
                                   c.angular ? "the base speed, deg/s" : "the base speed, mm/s");
  if (!speed) return speed.error();
  drive.base_speed = c.angular ? rad_from_deg(*speed) : *speed;
  auto force = servo_file_required(reader, node, path, units.force, ServoFileBound::positive,
                                   c.angular ? "the base torque, N·mm" : "the base force, N");
  if (!force) return force.error();
  drive.base_force = *force;

  auto inertia = servo_file_number(reader, node, path, "motor_inertia_kg_cm2", ServoFileBound::non_negative);
  if (!inertia) return inertia.error();
  drive.motor_inertia_kg_mm2 = inertia->value_or(0.0) * 100.0;
  auto transmission = servo_file_number(reader, node, path, units.transmission, ServoFileBound::positive);
  if (!transmission) return transmission.error();
  if (*transmission) {
    drive.motor_rad_per_unit = c.angular ? **transmission : 2.0 * kPi / **transmission;
  } else if (drive.motor_inertia_kg_mm2 > 0.0) {
    return reader.error_missing(node, path + "." + units.transmission,
                                c.angular ? "the gear ratio, motor turns per actuator turn, with "
                                            "motor_inertia_kg_cm2 > 0"
                                          : "the screw's lead, mm, with motor_inertia_kg_cm2 > 0");
  }

  auto error_max = servo_file_number(reader, node, path, units.error_max, ServoFileBound::positive);
  if (!error_max) return error_max.error();
  if (*error_max) drive.error_max = c.angular ? rad_from_deg(**error_max) : **error_max;
  auto command_max = servo_file_number(reader, node, path, "command_max", ServoFileBound::positive);
  if (!command_max) return command_max.error();
  if (*command_max) drive.command_max = **command_max;

  if (auto gains = servo_file_gains(c, node, path, drive); !gains) return gains.error();
  if (auto imperfect = servo_file_imperfections(c, node, path, drive); !imperfect) return imperfect.error();
  if (auto law = servo_file_characteristic(reader, node, path, drive); !law) return law.error();
  return drive;
}

// `drives:`: one mapping for every drive, or a list of one per actuator.
Status servo_file_drives(const ServoFileContext& c, const YAML::Node& section, ServoParameters& out) {
  const int count = out.drive_count;
  const YAML::Node node = section["drives"];
  const std::string what =
      fmt::format("one mapping for every drive or a list of {} mappings (one per actuator)", count);
  if (!node) return c.reader.error_missing(section, "servo.drives", what);
  if (node.IsMap()) {
    auto one = servo_file_drive(c, node, "servo.drives");
    if (!one) return one.error();
    std::fill(out.drives.begin(), out.drives.begin() + count, *one);
    return ok_status();
  }
  if (!node.IsSequence() || static_cast<int>(node.size()) != count) {
    const std::string message = node.IsSequence()
                                    ? fmt::format("expected {}, got a list of {}", what, node.size())
                                    : fmt::format("expected {}", what);
    return node.IsNull() ? servo_file_error_at_key(c.reader, section, "drives", "servo.drives", message)
                         : c.reader.error_at(node, "servo.drives", message);
  }
  for (int j = 0; j < count; ++j) {
    auto one = servo_file_drive(c, node[j], fmt::format("servo.drives[{}]", j));
    if (!one) return one.error();
    out.drives[j] = *one;
  }
  return ok_status();
}

}  // namespace

Result<ServoParameters> read_servo(const YAML::Node& root, const YamlReader& reader,
                                   const Mechanism& mechanism) {
  ServoParameters out;
  const YAML::Node node = root["servo"];
  if (!node) return out;
  if (!node.IsMap()) return reader.error_at_value(root, "servo", "expected a mapping (drives: …)");
  if (auto keys = reader.check_keys(
          node, "servo",
          {"tuning", "loop_period_ms", "velocity_feedforward", "sample_delay_periods", "drives"});
      !keys)
    return keys.error();
  out.line = yaml_key_line(root, "servo");
  out.drive_count = mechanism.actuator_count();

  if (node["tuning"]) {
    auto tuning = servo_file_tuning(reader, node);
    if (!tuning) return tuning.error();
    out.tuning = *tuning;
    out.tuning_line = yaml_key_line(node, "tuning");
  }
  // The drives' own loops run at least as often as the CNC's servo period at its slowest (drives.period_ms).
  auto period = servo_file_number(reader, node, "servo", "loop_period_ms", ServoFileBound::positive);
  if (!period) return period.error();
  if (*period) {
    if (**period > 20.0) {
      return reader.error_at(node["loop_period_ms"], "servo.loop_period_ms",
                             fmt::format("must be at most 20 ms, got {}", **period));
    }
    out.loop_period_s = **period * 1e-3;
    out.loop_period_line = yaml_key_line(node, "loop_period_ms");
  }
  auto feedforward =
      servo_file_number(reader, node, "servo", "velocity_feedforward", ServoFileBound::fraction);
  if (!feedforward) return feedforward.error();
  out.velocity_feedforward = feedforward->value_or(0.0);
  auto delay = servo_file_number(reader, node, "servo", "sample_delay_periods", ServoFileBound::non_negative);
  if (!delay) return delay.error();
  if (*delay) {
    if (**delay != std::floor(**delay) || **delay > kServoFileMaxDelay) {
      return reader.error_at(
          node["sample_delay_periods"], "servo.sample_delay_periods",
          fmt::format("must be a whole number of loop periods, 0 … {}, got {}", kServoFileMaxDelay, **delay));
    }
    out.sample_delay_periods = static_cast<int>(**delay);
  }

  const ServoFileContext context{reader, mechanism, mechanism.actuators_are_angles(), out.tuning};
  if (auto drives = servo_file_drives(context, node, out); !drives) return drives.error();
  return out;
}

}  // namespace pkm
