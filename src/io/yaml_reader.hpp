#pragma once
// pkm's one YAML reader (machine files, load files). Every failure is an Error whose message names the file,
// the line, the column and the key (with index): "machines/hex.yaml:7:5: base_joints[2]: expected 3
// numbers, got 2". parse_yaml_document() also refuses what yaml-cpp accepts silently: a key given twice
// (yaml-cpp would keep the first) and a key that is a list or a mapping.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace pkm {

/// The document in `text`, checked: every mapping key a plain scalar, no key twice in one mapping. Errors
/// (ErrorCode::bad_input): "FILE:LINE:COLUMN: KEY: reason", or "FILE:LINE:COLUMN: not valid YAML: reason".
Result<YAML::Node> parse_yaml_document(std::string_view text, const std::string& source_name);

/// The file through the guarded reader (io/input_file.hpp; `what` names it: "machine file"), parsed.
Result<YAML::Node> load_yaml_file(const std::string& path, std::string_view what);

/// The largest coordinate of a point in a YAML file: 1e9 (mm: a thousand kilometres), far beyond any machine.
inline constexpr double kMaxPointCoordinate = 1e9;

class YamlReader {
 public:
  explicit YamlReader(std::string source_name) : source_(std::move(source_name)) {}

  const std::string& source() const { return source_; }

  /// "FILE:LINE:COLUMN: KEY: message" for a node (1-based; just "FILE: KEY: message" if it has no mark).
  Error error_at(const YAML::Node& node, std::string_view key, std::string_view message) const;
  /// The same for the value of `key` in `parent`, at the key itself when the value is empty (`home:` with
  /// nothing after it has no place of its own, yaml-cpp would put it after the end of the file).
  Error error_at_value(const YAML::Node& parent, std::string_view key, std::string_view message) const;
  Error error_missing(const YAML::Node& parent, std::string_view key, std::string_view what) const;

  /// Rejects keys of a mapping that are not in `allowed` (typos must not be silently ignored).
  Status check_keys(const YAML::Node& mapping, std::string_view where,
                    std::initializer_list<std::string_view> allowed) const;

  Result<double> number(const YAML::Node& node, std::string_view key) const;
  Result<double> required_number(const YAML::Node& parent, std::string_view key) const;
  Result<std::optional<double>> optional_number(const YAML::Node& parent, std::string_view key) const;
  Result<std::string> required_string(const YAML::Node& parent, std::string_view key) const;
  /// A single word or text if the key is there (a list or a mapping is an error).
  Result<std::optional<std::string>> optional_string(const YAML::Node& parent, std::string_view key) const;
  /// optional_string for a label (`name`, `description`): one line of UTF-8 text, no control characters (a
  /// TAB, an escape sequence that would act on the terminal that prints it), nothing a JSON summary cannot
  /// hold.
  Result<std::optional<std::string>> optional_label(const YAML::Node& parent, std::string_view key) const;
  Result<int> required_integer(const YAML::Node& parent, std::string_view key) const;

  /// A list of exactly `dims` numbers (dims = 2 or 3); 2-number points get z = 0. Each at most
  /// kMaxPointCoordinate in size: the geometry squares and multiplies them, and 1e308 would overflow there
  /// and be blamed on whatever is computed from it (the home pose).
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
/// "FILE:LINE:COLUMN" of a node (1-based), or "FILE" when it has no mark.
std::string yaml_where(const std::string& source, const YAML::Node& node);
/// The 1-based line of `key` itself in a mapping, 0 if absent: a block value (`motion:` with its keys on the
/// lines below) starts on the line after its key.
int yaml_key_line(const YAML::Node& mapping, std::string_view key);

}  // namespace pkm
