// The `stiffness:` section: the struts' axial stiffness (a number or E·A/L), the joints' and the carriages'
// compliance, the model, and the frame of beams (frame_file.cpp); docs/machine-file.md, docs/stiffness.md.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include "io/machine_file_sections.hpp"

namespace pkm {
namespace {

// One strut: stiffness_N_mm, or modulus_N_mm2 with area_mm2; all positive.
Result<StrutStiffness> read_strut_stiffness(const YamlReader& reader, const YAML::Node& node,
                                            const std::string& path) {
  if (!node.IsMap()) return reader.error_at(node, path, "expected a mapping (stiffness_N_mm: …)");
  if (auto keys = reader.check_keys(node, path, {"stiffness_N_mm", "modulus_N_mm2", "area_mm2"}); !keys)
    return keys.error();
  StrutStiffness strut;
  const bool direct = static_cast<bool>(node["stiffness_N_mm"]);
  const bool section = node["modulus_N_mm2"] || node["area_mm2"];
  if (direct == section) {
    return reader.error_at(node, path,
                           direct ? "give stiffness_N_mm or modulus_N_mm2 with area_mm2, not both"
                                  : "expected stiffness_N_mm, or modulus_N_mm2 with area_mm2");
  }
  struct Field {
    const char* key;
    double* value;
  };
  const Field direct_fields[] = {{"stiffness_N_mm", &strut.stiffness_N_mm}};
  const Field section_fields[] = {{"modulus_N_mm2", &strut.modulus_N_mm2}, {"area_mm2", &strut.area_mm2}};
  const std::span<const Field> fields =
      direct ? std::span<const Field>(direct_fields) : std::span<const Field>(section_fields);
  for (const Field& field : fields) {
    const std::string name = path + "." + field.key;
    if (!node[field.key]) return reader.error_missing(node, name, "a positive number");
    auto value = reader.number(node[field.key], name);
    if (!value) return value.error();
    if (!(*value > 0.0) || !std::isfinite(*value))
      return reader.error_at(node[field.key], name, fmt::format("must be positive, got {}", *value));
    *field.value = *value;
  }
  return strut;
}

// A non-negative compliance (or positive stiffness, `positive`) under `key` of `node`, when given.
Status read_optional(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                     const char* key, bool positive, double& value) {
  if (!node[key]) return ok_status();
  const std::string name = path + "." + key;
  auto number = reader.number(node[key], name);
  if (!number) return number.error();
  const bool valid = std::isfinite(*number) && (positive ? *number > 0.0 : *number >= 0.0);
  if (!valid) {
    return reader.error_at(node[key], name,
                           fmt::format("must be {}, got {}", positive ? "positive" : "≥ 0", *number));
  }
  value = *number;
  return ok_status();
}

// The joints at one strut's ends: translational compliance at each end, rotational compliance (K_u, K_θ of
// Rusanov et al.), all ≥ 0 (0: a rigid joint).
Result<JointCompliance> read_joint_compliance(const YamlReader& reader, const YAML::Node& node,
                                              const std::string& path) {
  if (!node.IsMap()) return reader.error_at(node, path, "expected a mapping (base_compliance_mm_N: …)");
  if (auto keys = reader.check_keys(
          node, path, {"base_compliance_mm_N", "platform_compliance_mm_N", "rotational_compliance_rad_Nmm"});
      !keys)
    return keys.error();
  JointCompliance joint;
  if (auto s = read_optional(reader, node, path, "base_compliance_mm_N", false, joint.base_mm_N); !s)
    return s.error();
  if (auto s = read_optional(reader, node, path, "platform_compliance_mm_N", false, joint.platform_mm_N); !s)
    return s.error();
  if (auto s =
          read_optional(reader, node, path, "rotational_compliance_rad_Nmm", false, joint.rotational_rad_Nmm);
      !s)
    return s.error();
  return joint;
}

// One carriage of a glide machine: its drive's stiffness along the guide (> 0) and the guide's compliance
// across it (≥ 0); either may be left out (rigid).
Result<CarriageCompliance> read_carriage_compliance(const YamlReader& reader, const YAML::Node& node,
                                                    const std::string& path) {
  if (!node.IsMap()) return reader.error_at(node, path, "expected a mapping (drive_stiffness_N_mm: …)");
  if (auto keys = reader.check_keys(node, path, {"drive_stiffness_N_mm", "guide_compliance_mm_N"}); !keys)
    return keys.error();
  CarriageCompliance carriage;
  if (auto s = read_optional(reader, node, path, "drive_stiffness_N_mm", true, carriage.drive_stiffness_N_mm);
      !s)
    return s.error();
  if (auto s = read_optional(reader, node, path, "guide_compliance_mm_N", false, carriage.guide_mm_N); !s)
    return s.error();
  return carriage;
}

// `key`: one mapping for every strut, or a list of `count` mappings, each read by `read_one`.
template <class T, class ReadOne>
Status read_per_strut(const YamlReader& reader, const YAML::Node& section, const char* key, int count,
                      std::array<T, kMaxActuators>& out, ReadOne read_one) {
  const std::string path = std::string("stiffness.") + key;
  const YAML::Node node = section[key];
  if (node.IsMap()) {
    auto one = read_one(reader, node, path);
    if (!one) return one.error();
    std::fill(out.begin(), out.begin() + count, *one);
    return ok_status();
  }
  if (!node.IsSequence() || static_cast<int>(node.size()) != count) {
    const std::string message = fmt::format(
        "expected one mapping for every strut or a list of {} mappings (one per actuator)", count);
    // At the value when there is one; an empty value has no place of its own.
    return node.IsNull() ? reader.error_at_value(section, path, message)
                         : reader.error_at(node, path, message);
  }
  for (int j = 0; j < count; ++j) {
    auto one = read_one(reader, node[j], fmt::format("{}[{}]", path, j));
    if (!one) return one.error();
    out[j] = *one;
  }
  return ok_status();
}

// True when some strut's base joint rides on a carriage its drive moves (glide machines, rotopods).
bool has_moving_base_joints(const Mechanism& mechanism) {
  auto home = mechanism.inverse(mechanism.home());
  if (!home) return false;
  for (int j = 0; j < mechanism.actuator_count(); ++j) {
    Eigen::Vector3d first, second;
    mechanism.base_joint_motion(j, (*home)[j], first, second);
    if (first.squaredNorm() > 0.0) return true;
  }
  return false;
}

Result<StiffnessModel> read_model(const YamlReader& reader, const YAML::Node& section) {
  auto name = reader.required_string(section, "model");
  if (!name) return name.error();
  if (*name == "struts") return StiffnessModel::struts;
  if (*name == "struts_joints") return StiffnessModel::struts_joints;
  if (*name == "frame") return StiffnessModel::frame;
  return reader.error_at(section["model"], "stiffness.model",
                         fmt::format("expected struts, struts_joints or frame, got '{}'", *name));
}

}  // namespace

Result<StiffnessParameters> read_stiffness(const YAML::Node& root, const YamlReader& reader,
                                           const Mechanism& mechanism) {
  StiffnessParameters out;
  const YAML::Node node = root["stiffness"];
  if (!node) return out;
  if (!node.IsMap()) return reader.error_at_value(root, "stiffness", "expected a mapping (struts: …)");
  if (auto keys = reader.check_keys(node, "stiffness", {"struts", "joints", "carriages", "model", "frame"});
      !keys)
    return keys.error();
  out.line = yaml_key_line(root, "stiffness");
  const int count = mechanism.actuator_count();
  out.strut_count = count;
  if (!node["struts"]) return reader.error_missing(node, "stiffness.struts", "the struts' stiffness");
  if (auto s = read_per_strut(reader, node, "struts", count, out.struts, read_strut_stiffness); !s)
    return s.error();
  if (node["joints"]) {
    if (auto s = read_per_strut(reader, node, "joints", count, out.joints, read_joint_compliance); !s)
      return s.error();
  }
  if (node["carriages"]) {
    if (!has_moving_base_joints(mechanism)) {
      return reader.error_at(node["carriages"], "stiffness.carriages",
                             fmt::format("the {}'s struts do not ride on carriages: its drives' stiffness is "
                                         "the struts' own (stiffness.struts)",
                                         to_string(mechanism.type())));
    }
    if (auto s = read_per_strut(reader, node, "carriages", count, out.carriages, read_carriage_compliance);
        !s)
      return s.error();
  }
  // The frame of beams (stiffness.frame) is read here, before the model is chosen from what is given.
  auto frame = read_frame(node, reader, count);
  if (!frame) return frame.error();
  out.frame = std::move(*frame);
  const bool series = node["joints"] || node["carriages"];
  out.model = !out.frame.empty() ? StiffnessModel::frame
              : series           ? StiffnessModel::struts_joints
                                 : StiffnessModel::struts;
  if (node["model"]) {
    auto model = read_model(reader, node);
    if (!model) return model.error();
    if (*model == StiffnessModel::frame && out.frame.empty()) {
      return reader.error_at(node["model"], "stiffness.model",
                             "model: frame needs a frame: (stiffness.frame)");
    }
    out.model = *model;
  }
  return out;
}

}  // namespace pkm
