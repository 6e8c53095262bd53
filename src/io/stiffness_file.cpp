// The `stiffness:` section: the struts' axial stiffness, as a number or as E·A/L (docs/machine-file.md).
#include <fmt/format.h>

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

}  // namespace

Result<StiffnessParameters> read_stiffness(const YAML::Node& root, const YamlReader& reader,
                                           const Mechanism& mechanism) {
  StiffnessParameters out;
  const YAML::Node node = root["stiffness"];
  if (!node) return out;
  if (!node.IsMap()) return reader.error_at_value(root, "stiffness", "expected a mapping (struts: …)");
  if (auto keys = reader.check_keys(node, "stiffness", {"struts"}); !keys) return keys.error();
  out.line = yaml_key_line(root, "stiffness");
  const int count = mechanism.actuator_count();
  out.strut_count = count;
  const YAML::Node struts = node["struts"];
  if (!struts) return reader.error_missing(node, "stiffness.struts", "the struts' stiffness");
  if (struts.IsMap()) {
    auto strut = read_strut_stiffness(reader, struts, "stiffness.struts");
    if (!strut) return strut.error();
    std::fill(out.struts.begin(), out.struts.begin() + count, *strut);
    return out;
  }
  if (!struts.IsSequence() || static_cast<int>(struts.size()) != count) {
    const std::string message = fmt::format(
        "expected one mapping for every strut or a list of {} mappings (one per actuator)", count);
    // At the value when there is one; an empty value has no place of its own.
    return struts.IsNull() ? reader.error_at_value(node, "stiffness.struts", message)
                           : reader.error_at(struts, "stiffness.struts", message);
  }
  for (int j = 0; j < count; ++j) {
    auto strut = read_strut_stiffness(reader, struts[j], fmt::format("stiffness.struts[{}]", j));
    if (!strut) return strut.error();
    out.struts[j] = *strut;
  }
  return out;
}

}  // namespace pkm
