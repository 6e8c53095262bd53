#include "io/machine_file.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/units.hpp"
#include "io/calibration_file.hpp"
#include "io/input_file.hpp"
#include "io/machine_file_sections.hpp"
#include "machine/joint_limits.hpp"

namespace pkm {
namespace {

// As for the angles of --pose (io/pose_input.cpp): no machine turns a million degrees.
constexpr double kMaxHomeAngleDeg = 1e6;

bool is_planar(MechanismType type) {
  return type == MechanismType::planar2 || type == MechanismType::planar3;
}

void convert_limits_to_radians(ActuatorLimits& limits) {
  for (std::optional<double>* v : {&limits.min, &limits.max, &limits.speed, &limits.accel}) {
    if (*v) **v = rad_from_deg(**v);
  }
}

// The home pose: `count` numbers, x y (z) in mm and the angles in degrees (2: x y; 3: x y phi; 6: x y z and
// three angles). An angle beyond kMaxHomeAngleDeg is no orientation but a typo (1e300 would turn into a
// meaningless rotation without a word).
Result<std::optional<PoseVector>> read_home_pose(const YAML::Node& root, const YamlReader& reader,
                                                 int count) {
  if (!root["home"]) return std::optional<PoseVector>{};
  auto values = reader.numbers(root, "home", count);
  if (!values) return values.error();
  const int first_angle = count == 2 ? count : (count == 3 ? 2 : 3);
  for (int i = first_angle; i < count; ++i) {
    const double angle_deg = (*values)[static_cast<std::size_t>(i)];
    if (std::abs(angle_deg) > kMaxHomeAngleDeg) {
      return reader.error_at(
          root["home"][i], fmt::format("home[{}]", i),
          fmt::format("an angle of {:g} deg is not an orientation (at most {:g} deg in size)", angle_deg,
                      kMaxHomeAngleDeg));
    }
  }
  PoseVector h = PoseVector::Zero();
  if (count == 2) {
    h << (*values)[0], (*values)[1], 0, 0, 0, 0;
  } else if (count == 3) {
    h << (*values)[0], (*values)[1], 0, 0, 0, rad_from_deg((*values)[2]);
  } else {
    for (int i = 0; i < 6; ++i) h[i] = i < 3 ? (*values)[i] : rad_from_deg((*values)[i]);
  }
  return std::optional<PoseVector>{h};
}

// Unknown keys are errors: a misspelt key must not silently fall back to a default.
Status check_top_level_keys(const YAML::Node& root, const YamlReader& reader, const MechanismFileEntry& entry,
                            const std::string& type_name) {
  std::vector<std::string_view> allowed = {"name",   "description", "type",   "angles",     "tool",
                                           "limits", "motion",      "masses", "dynamics",   "drives",
                                           "home",   "stiffness",   "servo",  "calibration"};
  // Planar pin joints have no neutral axis to give.
  if (!is_planar(entry.type)) allowed.insert(allowed.end(), {"base_joint_axes", "platform_joint_axes"});
  allowed.insert(allowed.end(), entry.keys.begin(), entry.keys.end());
  for (const auto& item : root) {
    const std::string key = item.first.Scalar();  // a scalar: parse_yaml_document checked every key
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      return reader.error_at(item.first, key,
                             fmt::format("unknown key for type {} (allowed: {})", type_name, list));
    }
  }
  return ok_status();
}

// The home pose must itself be a valid configuration of the machine; fills the neutral joint axes, which
// default to the strut directions at home.
Status check_home_pose(const YAML::Node& root, const YamlReader& reader, Machine& machine) {
  auto home_actuators = machine.mechanism->inverse(machine.mechanism->home());
  const YAML::Node where = root["home"] ? root["home"] : root["type"];
  if (!home_actuators) {
    return reader.error_at(where, "home",
                           "the home pose is not reachable: " + home_actuators.error().message);
  }
  if (auto in_range = check_actuator_range(machine, *home_actuators); !in_range) {
    return reader.error_at(where, "home",
                           "the home pose is outside the actuator range: " + in_range.error().message);
  }
  auto axes = read_passive_joint_axes(root, reader, *machine.mechanism);
  if (!axes) return axes.error();
  machine.joint_axes = *axes;
  if (auto joints = check_joint_limits(machine, machine.mechanism->home()); !joints) {
    return reader.error_at(where, "home", "the home pose is beyond a joint limit: " + joints.error().message);
  }
  if (auto conditioning = check_conditioning_limit(machine, machine.mechanism->home()); !conditioning) {
    return reader.error_at(where, "home",
                           "the home pose is too badly conditioned: " + conditioning.error().message);
  }
  return ok_status();
}

// `angles:`, the convention of the file's three angles; planar mechanisms have one angle and no such key.
Result<AngleConvention> read_angle_convention(const YAML::Node& root, const YamlReader& reader, bool planar) {
  if (planar) {
    if (root["angles"])
      return reader.error_at(root["angles"], "angles",
                             "planar mechanisms have one angle, phi; remove this key");
    return AngleConvention::abc;
  }
  auto angles = reader.required_string(root, "angles");
  if (!angles) return angles.error();
  const auto parsed = angle_convention_from_string(*angles);
  if (!parsed) {
    return reader.error_at(
        root["angles"], "angles",
        fmt::format("unknown angle convention '{}' (known: abc | krylov | euler_zxz)", *angles));
  }
  return *parsed;
}

}  // namespace

Result<Machine> parse_machine_text(const std::string& yaml_text, const std::string& source_name) {
  YamlReader reader(source_name);
  auto document = parse_yaml_document(yaml_text, source_name);
  if (!document) return document.error();
  const YAML::Node root = *document;
  if (!root || !root.IsMap()) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}:1:1: expected a mapping with at least 'type:'", source_name));
  }

  auto type_name = reader.required_string(root, "type");
  if (!type_name) return type_name.error();
  const auto type = mechanism_type_from_string(*type_name);
  const MechanismFileEntry* entry = nullptr;
  for (const auto& e : mechanism_file_entries()) {
    if (type && e.type == *type) entry = &e;
  }
  if (!entry) {
    std::string known;
    for (const auto& e : mechanism_file_entries())
      known += (known.empty() ? "" : " | ") + std::string(to_string(e.type));
    return reader.error_at(root["type"], "type",
                           fmt::format("unknown mechanism '{}' (known: {})", *type_name, known));
  }

  if (Status keys = check_top_level_keys(root, reader, *entry, *type_name); !keys) return keys.error();

  auto convention = read_angle_convention(root, reader, is_planar(entry->type));
  if (!convention) return convention.error();

  // Free texts, but texts: a list here is a mistake the report would show as "[1, 2]".
  auto name = reader.optional_label(root, "name");
  if (!name) return name.error();
  if (auto description = reader.optional_label(root, "description"); !description) return description.error();

  Eigen::Vector3d tool = Eigen::Vector3d::Zero();
  if (root["tool"]) {
    auto t = reader.point(root["tool"], "tool", is_planar(entry->type) ? 2 : 3);
    if (!t) return t.error();
    tool = *t;
  }

  auto limits = read_limits(root, reader, is_planar(entry->type));
  if (!limits) return limits.error();
  auto motion = read_motion_settings(root, reader, is_planar(entry->type));
  if (!motion) return motion.error();
  auto masses = read_mass_properties(root, reader, is_planar(entry->type));
  if (!masses) return masses.error();

  auto home = read_home_pose(root, reader, entry->home_values);
  if (!home) return home.error();

  const MechanismSpec spec{root, reader, *convention, tool, *home, limits->actuators};
  auto drawn = entry->build(spec);
  if (!drawn) return drawn.error();
  // The calibrated values replace the drawing's before anything checks the machine at its home.
  auto mechanism = apply_calibration_section(root, reader, std::move(drawn.value()));
  if (!mechanism) return mechanism.error();

  Machine machine;
  machine.source = source_name;
  machine.name = name->value_or(*type_name);
  machine.mechanism = std::move(mechanism.value());
  machine.limits = limits->actuators;
  if (machine.mechanism->actuators_are_angles()) convert_limits_to_radians(machine.limits);
  machine.joint_limits = limits->joints;
  machine.motion = *motion;
  machine.masses = *masses;
  auto drives = read_drive_settings(root, reader, machine.mechanism->actuators_are_angles());
  if (!drives) return drives.error();
  machine.drives = *drives;
  // After the mechanism: the struts are one per actuator, and which parts a strut has depends on the type.
  auto dynamics = read_dynamics(root, reader, *machine.mechanism, is_planar(entry->type));
  if (!dynamics) return dynamics.error();
  machine.dynamics = *dynamics;
  auto stiffness = read_stiffness(root, reader, *machine.mechanism);
  if (!stiffness) return stiffness.error();
  machine.stiffness = *stiffness;
  auto servo = read_servo(root, reader, *machine.mechanism);
  if (!servo) return servo.error();
  machine.servo = *servo;
  machine.home_given = home->has_value();

  if (Status valid = check_home_pose(root, reader, machine); !valid) return valid.error();
  return machine;
}

Result<Machine> load_machine_file(const std::string& path) {
  auto text = read_text_input(path, "machine file");
  if (!text) return text.error();
  return parse_machine_text(*text, path);
}

}  // namespace pkm
