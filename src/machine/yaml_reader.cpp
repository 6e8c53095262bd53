#include "machine/yaml_reader.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm {

int yaml_line(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? mark.line + 1 : 0;
}

int yaml_key_line(const YAML::Node& mapping, std::string_view key) {
  if (!mapping.IsMap()) return 0;
  for (const auto& item : mapping) {
    if (item.first.IsScalar() && item.first.Scalar() == key) return yaml_line(item.first);
  }
  return 0;
}

Error YamlReader::error_at(const YAML::Node& node, std::string_view key, std::string_view message) const {
  return make_error(ErrorCode::bad_input,
                    fmt::format("{}:{}: {}: {}", source_, yaml_line(node), key, message));
}

Error YamlReader::error_missing(const YAML::Node& parent, std::string_view key, std::string_view what) const {
  return make_error(ErrorCode::bad_input,
                    fmt::format("{}:{}: {}: missing (expected {})", source_, yaml_line(parent), key, what));
}

Status YamlReader::check_keys(const YAML::Node& mapping, std::string_view where,
                              std::initializer_list<std::string_view> allowed) const {
  if (!mapping.IsMap()) return error_at(mapping, where, "expected a mapping of keys");
  for (const auto& entry : mapping) {
    const std::string key = entry.first.as<std::string>();
    bool known = false;
    for (std::string_view a : allowed) known = known || a == key;
    if (!known) {
      std::string list;
      for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      const std::string full_key = where.empty() ? key : fmt::format("{}.{}", where, key);
      return error_at(entry.first, full_key, fmt::format("unknown key (allowed here: {})", list));
    }
  }
  return ok_status();
}

Result<double> YamlReader::number(const YAML::Node& node, std::string_view key) const {
  if (!node.IsScalar()) return error_at(node, key, "expected a number");
  double value = 0.0;
  if (!YAML::convert<double>::decode(node, value)) {
    return error_at(node, key, fmt::format("expected a number, got '{}'", node.Scalar()));
  }
  if (!std::isfinite(value)) return error_at(node, key, "expected a finite number");
  return value;
}

Result<double> YamlReader::required_number(const YAML::Node& parent, std::string_view key) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return error_missing(parent, key, "a number");
  return number(node, key);
}

Result<std::optional<double>> YamlReader::optional_number(const YAML::Node& parent,
                                                          std::string_view key) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return std::optional<double>{};
  auto value = number(node, key);
  if (!value) return value.error();
  return std::optional<double>{*value};
}

Result<std::string> YamlReader::required_string(const YAML::Node& parent, std::string_view key) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return error_missing(parent, key, "a value");
  if (!node.IsScalar()) return error_at(node, key, "expected a single word");
  return node.Scalar();
}

Result<int> YamlReader::required_integer(const YAML::Node& parent, std::string_view key) const {
  auto value = required_number(parent, key);
  if (!value) return value.error();
  if (std::floor(*value) != *value) {
    return error_at(parent[std::string(key)], key, fmt::format("expected a whole number, got {}", *value));
  }
  return static_cast<int>(*value);
}

Result<Eigen::Vector3d> YamlReader::point(const YAML::Node& node, std::string_view key, int dims) const {
  if (!node.IsSequence()) return error_at(node, key, fmt::format("expected a list of {} numbers", dims));
  if (static_cast<int>(node.size()) != dims) {
    return error_at(node, key, fmt::format("expected {} numbers, got {}", dims, node.size()));
  }
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < dims; ++i) {
    auto v = number(node[i], fmt::format("{}[{}]", key, i));
    if (!v) return v.error();
    p[i] = *v;
  }
  return p;
}

Result<Eigen::Vector3d> YamlReader::required_point(const YAML::Node& parent, std::string_view key,
                                                   int dims) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return error_missing(parent, key, fmt::format("a list of {} numbers", dims));
  return point(node, key, dims);
}

Result<std::vector<Eigen::Vector3d>> YamlReader::points(const YAML::Node& parent, std::string_view key,
                                                        int count, int dims) const {
  const YAML::Node node = parent[std::string(key)];
  const std::string what = count > 0 ? fmt::format("a list of {} points of {} numbers", count, dims)
                                     : fmt::format("a list of points of {} numbers", dims);
  if (!node) return error_missing(parent, key, what);
  if (!node.IsSequence()) return error_at(node, key, "expected " + what);
  if ((count > 0 && static_cast<int>(node.size()) != count) || node.size() == 0) {
    return error_at(node, key, fmt::format("expected {}, got {} points", what, node.size()));
  }
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    auto p = point(node[i], fmt::format("{}[{}]", key, i), dims);
    if (!p) return p.error();
    out.push_back(*p);
  }
  return out;
}

Result<std::vector<double>> YamlReader::numbers(const YAML::Node& parent, std::string_view key,
                                                int count) const {
  const YAML::Node node = parent[std::string(key)];
  const std::string what = count > 0 ? fmt::format("a list of {} numbers", count) : "a list of numbers";
  if (!node) return error_missing(parent, key, what);
  if (!node.IsSequence()) return error_at(node, key, "expected " + what);
  if ((count > 0 && static_cast<int>(node.size()) != count) || node.size() == 0) {
    return error_at(node, key, fmt::format("expected {}, got {}", what, node.size()));
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    auto v = number(node[i], fmt::format("{}[{}]", key, i));
    if (!v) return v.error();
    out.push_back(*v);
  }
  return out;
}

}  // namespace pkm
