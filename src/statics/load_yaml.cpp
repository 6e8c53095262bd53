// Load files (--load @FILE): a default load case and load cases for ranges of program lines, in YAML.
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>

#include "io/yaml_reader.hpp"
#include "statics/load_keys.hpp"
#include "statics/load_model.hpp"

namespace pkm::statics {
namespace {

// The load keys on top of the machine files' YamlReader, so that both kinds of file report errors alike.
class LoadYamlReader {
 public:
  explicit LoadYamlReader(const std::string& source) : yaml_(source) {}

  // "FILE:LINE:COLUMN: KEY: message", 1-based.
  Error error_at(const YAML::Node& node, std::string_view key, std::string_view message) const {
    return yaml_.error_at(node, key, message);
  }

  Result<double> number(const YAML::Node& node, std::string_view key) const {
    return yaml_.number(node, key);
  }

  Result<Eigen::Vector3d> vector(const YAML::Node& node, std::string_view key) const {
    if (!node.IsSequence() || node.size() != 3) {
      return error_at(node, key, fmt::format("expected [x, y, z], got '{}'", describe(node)));
    }
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      auto x = number(node[i], fmt::format("{}[{}]", key, i));
      if (!x) return x.error();
      v[i] = *x;
    }
    return v;
  }

  // The case's keys from `node` on top of `load`; `where` prefixes keys in messages; `lines` (blocks only) is
  // skipped here and read by the caller.
  Status load_case(const YAML::Node& node, std::string_view where, bool allow_lines,
                   CuttingLoad& load) const {
    if (!node.IsMap()) return error_at(node, where, "expected a mapping of load keys");
    for (const auto& entry : node) {  // parse_yaml_document refused keys given twice
      const std::string key = entry.first.Scalar();
      const std::string full = fmt::format("{}.{}", where, key);
      const YAML::Node value = entry.second;
      if (allow_lines && key == "lines") continue;
      if (double* field = load_number_field(load, key)) {
        auto v = number(value, full);
        if (!v) return v.error();
        if (auto problem = load_number_problem(key, *v)) return error_at(value, full, *problem);
        *field = *v;
      } else if (Eigen::Vector3d* vec = load_vector_field(load, key)) {
        auto v = vector(value, full);
        if (!v) return v.error();
        for (int i = 0; i < 3; ++i) {
          if (auto problem = load_number_problem(key, (*v)[i]))
            return error_at(value[i], fmt::format("{}[{}]", full, i), *problem);
        }
        *vec = *v;
      } else if (key == "contact") {
        const auto side = value.IsScalar() ? contact_side_from_word(value.Scalar()) : std::nullopt;
        if (!side) {
          return error_at(value, full, fmt::format("expected left or right, got '{}'", describe(value)));
        }
        load.contact_side = *side;
      } else {
        return error_at(
            entry.first, full,
            fmt::format("unknown key (allowed: {}{})", allow_lines ? "lines, " : "", load_key_list()));
      }
    }
    return ok_status();
  }

  Result<BlockLoad> block(const YAML::Node& node, std::string_view where, const CuttingLoad& start) const {
    BlockLoad b;
    b.load = start;
    if (auto read = load_case(node, where, true, b.load); !read) return read.error();
    const std::string key = fmt::format("{}.lines", where);
    const YAML::Node lines = node["lines"];
    if (!lines) return error_at(node, key, "missing (expected [FIRST, LAST] program lines)");
    if (!lines.IsSequence() || lines.size() != 2) {
      return error_at(lines, key, fmt::format("expected [FIRST, LAST], got '{}'", describe(lines)));
    }
    int bounds[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
      auto v = number(lines[i], key);
      if (!v) return v.error();
      if (std::floor(*v) != *v || *v < 1 || *v > std::numeric_limits<int>::max()) {
        return error_at(lines[i], key, fmt::format("expected a program line number (1, 2, ...), got {}", *v));
      }
      bounds[i] = static_cast<int>(*v);
    }
    if (bounds[0] > bounds[1]) {
      return error_at(lines, key,
                      fmt::format("FIRST must not be after LAST, got [{}, {}]", bounds[0], bounds[1]));
    }
    b.first_line = bounds[0];
    b.last_line = bounds[1];
    b.location = ErrorLocation{yaml_.source(), yaml_line(lines), lines.Mark().column + 1, key};
    return b;
  }

 private:
  static std::string describe(const YAML::Node& node) {
    if (node.IsScalar()) return node.Scalar();
    if (node.IsSequence()) return fmt::format("a list of {}", node.size());
    if (node.IsMap()) return "a mapping";
    return "nothing";
  }

  YamlReader yaml_;
};

}  // namespace

Result<LoadModel> parse_load_yaml(const std::string& text, const std::string& source_name) {
  auto document = parse_yaml_document(text, source_name);
  if (!document) return document.error();
  const YAML::Node root = *document;
  if (!root || !root.IsMap()) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{}:1:1: expected a mapping with 'default:' and/or 'blocks:'", source_name));
  }
  const LoadYamlReader reader(source_name);
  for (const auto& entry : root) {
    const std::string key = entry.first.Scalar();
    if (key != "default" && key != "blocks") {
      return reader.error_at(entry.first, key, "unknown key (allowed: default, blocks)");
    }
  }
  LoadModel model;
  // The default first, wherever it stands: every block starts from it.
  if (const YAML::Node d = root["default"]) {
    if (auto read = reader.load_case(d, "default", false, model.default_load); !read) return read.error();
  }
  if (const YAML::Node blocks = root["blocks"]) {
    if (!blocks.IsSequence()) return reader.error_at(blocks, "blocks", "expected a list of load cases");
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      auto b = reader.block(blocks[i], fmt::format("blocks[{}]", i), model.default_load);
      if (!b) return b.error();
      model.blocks.push_back(*b);
    }
  }
  return model;
}

}  // namespace pkm::statics
