#pragma once
// Typed reads from a YAML machine file. Every failure is an Error whose message names the file, the line and
// the key (with index), e.g. "machines/hex.yaml:7: base_joints[2]: expected 3 numbers, got 2".
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace pkm {

class YamlReader {
 public:
  explicit YamlReader(std::string source_name) : source_(std::move(source_name)) {}

  const std::string& source() const { return source_; }

  /// "FILE:LINE: KEY: message" for a node (line of the node, 1-based).
  Error error_at(const YAML::Node& node, std::string_view key, std::string_view message) const;
  Error error_missing(const YAML::Node& parent, std::string_view key, std::string_view what) const;

  /// Rejects keys of a mapping that are not in `allowed` (typos must not be silently ignored).
  Status check_keys(const YAML::Node& mapping, std::string_view where,
                    std::initializer_list<std::string_view> allowed) const;

  Result<double> number(const YAML::Node& node, std::string_view key) const;
  Result<double> required_number(const YAML::Node& parent, std::string_view key) const;
  Result<std::optional<double>> optional_number(const YAML::Node& parent, std::string_view key) const;
  Result<std::string> required_string(const YAML::Node& parent, std::string_view key) const;
  Result<int> required_integer(const YAML::Node& parent, std::string_view key) const;

  /// A list of exactly `dims` numbers (dims = 2 or 3); 2-number points get z = 0.
  Result<Eigen::Vector3d> point(const YAML::Node& node, std::string_view key, int dims) const;
  Result<Eigen::Vector3d> required_point(const YAML::Node& parent, std::string_view key, int dims) const;
  /// A list of `count` points (count < 0: any number ≥ 1) of `dims` numbers each.
  Result<std::vector<Eigen::Vector3d>> points(const YAML::Node& parent, std::string_view key, int count,
                                              int dims) const;
  /// A list of numbers; count < 0: any length ≥ 1.
  Result<std::vector<double>> numbers(const YAML::Node& parent, std::string_view key, int count) const;

 private:
  std::string source_;
};

/// The 1-based line of a node in its file (0 when the node has no mark).
int yaml_line(const YAML::Node& node);
/// The 1-based line of `key` itself in a mapping, 0 if absent: a block value (`motion:` with its keys on the
/// lines below) starts on the line after its key.
int yaml_key_line(const YAML::Node& mapping, std::string_view key);

}  // namespace pkm
