// The `stiffness.frame` section: the machine frame as beams between named nodes (docs/stiffness_frame.md).
//
//   frame:
//     sections:                       # named sections, or a mapping in place of a beam's section name
//       column: {modulus_N_mm2: 210000, shear_modulus_N_mm2: 81000, area_mm2: 4000,
//                second_moment_x_mm4: 1.2e7, second_moment_y_mm4: 1.2e7, torsion_constant_mm4: 1.9e7}
//     nodes:
//       - {name: foot1, position_mm: [450, 0, -600], fixed: true}
//       - {name: top1, position_mm: [450, 0, 0]}
//     beams:
//       - {from: foot1, to: top1, section: column, section_x: [1, 0, 0]}
//     base_joint_nodes: [top1, top1, top2, top2, top3, top3]   # one per strut
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <string>

#include "io/machine_file_sections.hpp"

namespace pkm {
namespace {

// Beams shorter than this (mm) have coincident ends: no direction, no stiffness.
constexpr double kShortestBeam_mm = 1e-9;

// The error at the value of `key` in `parent` under its full name `path` (at the key when the value is
// empty).
Error frame_value_error(const YamlReader& reader, const YAML::Node& parent, const std::string& key,
                        const std::string& path, const std::string& message) {
  const YAML::Node value = parent[key];
  if (value && !value.IsNull()) return reader.error_at(value, path, message);
  for (const auto& item : parent) {
    if (item.first.Scalar() == key) return reader.error_at(item.first, path, message);
  }
  return reader.error_at(parent, path, message);
}

Result<double> read_frame_positive(const YamlReader& reader, const YAML::Node& parent, const std::string& key,
                                   const std::string& path) {
  const std::string name = path + "." + key;
  if (!parent[key]) return reader.error_missing(parent, name, "a positive number");
  auto value = reader.number(parent[key], name);
  if (!value) return value.error();
  if (!(*value > 0.0) || !std::isfinite(*value))
    return reader.error_at(parent[key], name, fmt::format("must be positive, got {}", *value));
  return *value;
}

Result<BeamSection> read_frame_section(const YamlReader& reader, const YAML::Node& node,
                                       const std::string& path) {
  if (!node.IsMap()) return reader.error_at(node, path, "expected a mapping (modulus_N_mm2: …)");
  if (auto keys = reader.check_keys(node, path,
                                    {"modulus_N_mm2", "shear_modulus_N_mm2", "area_mm2",
                                     "second_moment_x_mm4", "second_moment_y_mm4", "torsion_constant_mm4"});
      !keys)
    return keys.error();
  BeamSection section;
  struct Field {
    const char* key;
    double* value;
  };
  const Field fields[] = {{"modulus_N_mm2", &section.modulus_N_mm2},
                          {"shear_modulus_N_mm2", &section.shear_modulus_N_mm2},
                          {"area_mm2", &section.area_mm2},
                          {"second_moment_x_mm4", &section.second_moment_x_mm4},
                          {"second_moment_y_mm4", &section.second_moment_y_mm4},
                          {"torsion_constant_mm4", &section.torsion_constant_mm4}};
  for (const Field& field : fields) {
    auto value = read_frame_positive(reader, node, field.key, path);
    if (!value) return value.error();
    *field.value = *value;
  }
  return section;
}

Result<FrameNode> read_frame_node(const YamlReader& reader, const YAML::Node& node, const std::string& path) {
  if (!node.IsMap()) return reader.error_at(node, path, "expected a mapping (name: …, position_mm: […])");
  if (auto keys = reader.check_keys(node, path, {"name", "position_mm", "fixed"}); !keys) return keys.error();
  FrameNode out;
  out.line = yaml_line(node);
  if (!node["name"]) return reader.error_missing(node, path + ".name", "a node name");
  if (!node["name"].IsScalar() || node["name"].Scalar().empty())
    return frame_value_error(reader, node, "name", path + ".name", "expected a node name (one word)");
  out.name = node["name"].Scalar();
  if (!node["position_mm"]) return reader.error_missing(node, path + ".position_mm", "a list of 3 numbers");
  auto position = reader.point(node["position_mm"], path + ".position_mm", 3);
  if (!position) return position.error();
  out.position_mm = *position;
  if (const YAML::Node fixed = node["fixed"]) {
    if (!fixed.IsScalar() || !YAML::convert<bool>::decode(fixed, out.fixed))
      return reader.error_at(fixed, path + ".fixed", "expected true or false");
  }
  return out;
}

// A node named by `node` (a scalar), as its index.
Result<int> read_frame_node_name(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                                 const std::map<std::string, int>& names) {
  if (!node.IsScalar()) return reader.error_at(node, path, "expected a node name");
  const auto found = names.find(node.Scalar());
  if (found == names.end())
    return reader.error_at(node, path,
                           fmt::format("unknown node '{}' (not in stiffness.frame.nodes)", node.Scalar()));
  return found->second;
}

Result<FrameBeam> read_frame_beam(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                                  const std::vector<FrameNode>& nodes,
                                  const std::map<std::string, int>& names,
                                  const std::map<std::string, BeamSection>& sections) {
  if (!node.IsMap()) return reader.error_at(node, path, "expected a mapping (from: …, to: …, section: …)");
  if (auto keys = reader.check_keys(node, path, {"from", "to", "section", "section_x"}); !keys)
    return keys.error();
  FrameBeam beam;
  beam.line = yaml_line(node);
  for (const char* end : {"from", "to"}) {
    if (!node[end]) return reader.error_missing(node, path + "." + end, "a node name");
    auto index = read_frame_node_name(reader, node[end], path + "." + end, names);
    if (!index) return index.error();
    (std::string(end) == "from" ? beam.from : beam.to) = *index;
  }
  const Eigen::Vector3d axis = nodes[beam.to].position_mm - nodes[beam.from].position_mm;
  if (!(axis.norm() > kShortestBeam_mm)) {
    return reader.error_at(node, path,
                           fmt::format("the beam from '{}' to '{}' has zero length", nodes[beam.from].name,
                                       nodes[beam.to].name));
  }
  const YAML::Node section = node["section"];
  if (!section) return reader.error_missing(node, path + ".section", "a section name or a section mapping");
  if (section.IsScalar()) {
    const auto found = sections.find(section.Scalar());
    if (found == sections.end()) {
      return reader.error_at(
          section, path + ".section",
          fmt::format("unknown section '{}' (not in stiffness.frame.sections)", section.Scalar()));
    }
    beam.section = found->second;
  } else {
    auto inline_section = read_frame_section(reader, section, path + ".section");
    if (!inline_section) return inline_section.error();
    beam.section = *inline_section;
  }
  // The section's x axis: given, or the base z axis, or the base x axis for a beam along z.
  const Eigen::Vector3d unit = axis.normalized();
  beam.section_x = std::abs(unit.z()) < 0.999 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  if (const YAML::Node x = node["section_x"]) {
    auto given = reader.point(x, path + ".section_x", 3);
    if (!given) return given.error();
    const double across = given->cross(unit).norm();
    if (!(across > 1e-6 * given->norm()))
      return reader.error_at(x, path + ".section_x", "must not be parallel to the beam (nor zero)");
    beam.section_x = *given;
  }
  return beam;
}

}  // namespace

Result<FrameParameters> read_frame(const YAML::Node& stiffness, const YamlReader& reader, int strut_count) {
  FrameParameters out;
  const YAML::Node node = stiffness["frame"];
  if (!node) return out;
  const std::string path = "stiffness.frame";
  if (!node.IsMap())
    return frame_value_error(reader, stiffness, "frame", path, "expected a mapping (nodes: …, beams: …)");
  if (auto keys = reader.check_keys(node, path, {"sections", "nodes", "beams", "base_joint_nodes"}); !keys)
    return keys.error();
  out.source = reader.source();
  out.line = yaml_key_line(stiffness, "frame");

  std::map<std::string, BeamSection> sections;
  if (const YAML::Node list = node["sections"]) {
    if (!list.IsMap())
      return frame_value_error(reader, node, "sections", path + ".sections",
                               "expected a mapping of named sections");
    for (const auto& item : list) {
      const std::string name = item.first.Scalar();
      auto section = read_frame_section(reader, item.second, path + ".sections." + name);
      if (!section) return section.error();
      sections[name] = *section;
    }
  }

  const YAML::Node nodes = node["nodes"];
  if (!nodes) return reader.error_missing(node, path + ".nodes", "a list of nodes");
  if (!nodes.IsSequence() || nodes.size() == 0)
    return frame_value_error(reader, node, "nodes", path + ".nodes",
                             "expected a list of nodes (name, position_mm, fixed)");
  std::map<std::string, int> names;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string where = fmt::format("{}.nodes[{}]", path, i);
    auto frame_node = read_frame_node(reader, nodes[i], where);
    if (!frame_node) return frame_node.error();
    if (!names.emplace(frame_node->name, static_cast<int>(i)).second)
      return reader.error_at(nodes[i]["name"], where + ".name",
                             fmt::format("node '{}' is named twice", frame_node->name));
    out.nodes.push_back(*frame_node);
  }

  if (const YAML::Node beams = node["beams"]) {
    if (!beams.IsSequence())
      return frame_value_error(reader, node, "beams", path + ".beams", "expected a list of beams");
    for (std::size_t i = 0; i < beams.size(); ++i) {
      auto beam =
          read_frame_beam(reader, beams[i], fmt::format("{}.beams[{}]", path, i), out.nodes, names, sections);
      if (!beam) return beam.error();
      out.beams.push_back(*beam);
    }
  }

  const YAML::Node carriers = node["base_joint_nodes"];
  if (!carriers) return reader.error_missing(node, path + ".base_joint_nodes", "one node name per strut");
  if (!carriers.IsSequence() || static_cast<int>(carriers.size()) != strut_count) {
    return frame_value_error(reader, node, "base_joint_nodes", path + ".base_joint_nodes",
                             fmt::format("expected a list of {} node names (one per strut)", strut_count));
  }
  for (int j = 0; j < strut_count; ++j) {
    auto index =
        read_frame_node_name(reader, carriers[j], fmt::format("{}.base_joint_nodes[{}]", path, j), names);
    if (!index) return index.error();
    out.strut_nodes.push_back(*index);
  }
  return out;
}

}  // namespace pkm
