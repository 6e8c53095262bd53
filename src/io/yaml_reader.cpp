#include "io/yaml_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <unordered_map>

#include "io/input_file.hpp"
#include "io/printable_text.hpp"
#include "io/yaml_stream_check.hpp"

namespace pkm {

namespace {

// The error with its place as fields too (core/result.hpp); the message is made by the caller.
Error located_yaml_error(const std::string& source, const YAML::Mark& mark, std::string_view key,
                         std::string message) {
  Error error = make_error(ErrorCode::bad_input, std::move(message));
  error.location.file = source;
  if (!mark.is_null() && mark.line >= 0) {
    error.location.line = mark.line + 1;
    error.location.column = mark.column + 1;
  }
  error.location.key = std::string(key);
  return error;
}

}  // namespace

namespace {

std::string yaml_mark_text(const YAML::Mark& mark) {
  return fmt::format("{}:{}", mark.line + 1, mark.column + 1);
}

std::string yaml_child_key(std::string_view parent, std::string_view key) {
  return parent.empty() ? std::string(key) : fmt::format("{}.{}", parent, key);
}

// What yaml-cpp lets through: a key that is a list or a mapping (`[a]: 1`), which no pkm file has and which
// the readers could not name, and a key given twice, of which yaml-cpp keeps the first without a word.
Status check_yaml_node(const YAML::Node& node, const std::string& where, const std::string& source) {
  if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      if (auto checked = check_yaml_node(node[i], fmt::format("{}[{}]", where, i), source); !checked)
        return checked;
    }
  } else if (node.IsMap()) {
    std::unordered_map<std::string, int> first_line;
    for (const auto& item : node) {
      if (!item.first.IsScalar()) {
        return located_yaml_error(
            source, item.first.Mark(), where,
            fmt::format("{}: {}: a key must be a plain word, not a {}", yaml_where(source, item.first),
                        where.empty() ? "(top level)" : where, item.first.IsSequence() ? "list" : "mapping"));
      }
      const std::string key = yaml_child_key(where, item.first.Scalar());
      const auto [seen, inserted] = first_line.emplace(item.first.Scalar(), yaml_line(item.first));
      if (!inserted) {
        return located_yaml_error(source, item.first.Mark(), key,
                                  fmt::format("{}: {}: given twice (first on line {})",
                                              yaml_where(source, item.first), key, seen->second));
      }
      if (auto checked = check_yaml_node(item.second, key, source); !checked) return checked;
    }
  }
  return ok_status();
}

// yaml-cpp reads ahead before it notices the depth, so its mark can lie past the end of the file. For the
// usual case, brackets nested too deep ([[[[...), the place is the bracket that opens the level too many;
// otherwise yaml-cpp's mark, kept inside the text.
YAML::Mark yaml_deep_nesting_mark(std::string_view text, const YAML::DeepRecursion& e) {
  YAML::Mark mark;
  mark.line = mark.column = 0;
  int depth = 0;
  char quote = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '{') {
      if (++depth >= e.depth() - 1) return mark;
    } else if (c == ']' || c == '}') {
      --depth;
    }
    if (c == '\n') {
      ++mark.line;
      mark.column = 0;
    } else {
      ++mark.column;
    }
  }
  YAML::Mark clamped = e.mark;
  const auto last_line = static_cast<int>(std::count(text.begin(), text.end(), '\n')) -
                         (!text.empty() && text.back() == '\n' ? 1 : 0);
  if (clamped.line > last_line) {
    clamped.line = std::max(last_line, 0);
    clamped.column = 0;
  }
  return clamped;
}

// yaml-cpp reads a NUL byte as the start of an escape: "a\0tb" becomes "a", a TAB and "b" without a word.
std::optional<Error> yaml_nul_byte(std::string_view text, const std::string& source) {
  const std::size_t at = text.find('\0');
  if (at == std::string_view::npos) return std::nullopt;
  const std::size_t line_start =
      text.rfind('\n', at) == std::string_view::npos ? 0 : text.rfind('\n', at) + 1;
  YAML::Mark mark;
  mark.line =
      static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
  mark.column = static_cast<int>(at - line_start);
  return located_yaml_error(source, mark, "",
                            fmt::format("{}:{}: not valid YAML: a NUL byte (\\x00); a YAML file is text",
                                        source, yaml_mark_text(mark)));
}

}  // namespace

Result<YAML::Node> parse_yaml_document(std::string_view text, const std::string& source_name) {
  YAML::Node root;
  // The events first: a tree with an alias cycle or a bomb must never be built, let alone walked.
  YamlStreamCheck stream(text, source_name);
  try {
    stream.run();
    if (stream.found()) return *stream.found();
    root = YAML::Load(std::string(text));
  } catch (const YAML::DeepRecursion& e) {
    const YAML::Mark mark = yaml_deep_nesting_mark(text, e);
    return located_yaml_error(source_name, mark, "",
                              fmt::format("{}:{}: not valid YAML: nested more than {} levels deep",
                                          source_name, yaml_mark_text(mark), e.depth() - 1));
  } catch (const YAML::Exception& e) {
    // An unclosed quote or bracket, a NUL byte or a TAB is the cause; yaml-cpp blames where it stopped.
    if (stream.found()) return *stream.found();
    if (auto nul = yaml_nul_byte(text, source_name)) return *nul;  // the usual cause: "unknown escape"
    if (auto cause = stream.explain(e)) return *cause;
    const std::string where =
        e.mark.is_null() ? source_name : fmt::format("{}:{}", source_name, yaml_mark_text(e.mark));
    return located_yaml_error(source_name, e.mark, "", fmt::format("{}: not valid YAML: {}", where, e.msg));
  }
  if (auto checked = check_yaml_node(root, "", source_name); !checked) return checked.error();
  // After the mapping is known, so that a binary file is still refused as "expected a mapping".
  if (root.IsMap()) {
    if (auto nul = yaml_nul_byte(text, source_name)) return *nul;
  }
  return root;
}

Result<YAML::Node> load_yaml_file(const std::string& path, std::string_view what) {
  auto text = read_text_input(path, what);
  if (!text) return text.error();
  return parse_yaml_document(*text, path);
}

std::string yaml_where(const std::string& source, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() || mark.line < 0 ? source : fmt::format("{}:{}", source, yaml_mark_text(mark));
}

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
  return located_yaml_error(source_, node.Mark(), key,
                            fmt::format("{}: {}: {}", yaml_where(source_, node), key, message));
}

Error YamlReader::error_at_value(const YAML::Node& parent, std::string_view key,
                                 std::string_view message) const {
  const YAML::Node value = parent[std::string(key)];
  if (value && !value.IsNull()) return error_at(value, key, message);
  if (parent.IsMap()) {
    for (const auto& item : parent) {
      if (item.first.IsScalar() && item.first.Scalar() == key) return error_at(item.first, key, message);
    }
  }
  return error_at(parent, key, message);
}

Error YamlReader::error_missing(const YAML::Node& parent, std::string_view key, std::string_view what) const {
  return located_yaml_error(
      source_, parent.Mark(), key,
      fmt::format("{}: {}: missing (expected {})", yaml_where(source_, parent), key, what));
}

Status YamlReader::check_keys(const YAML::Node& mapping, std::string_view where,
                              std::initializer_list<std::string_view> allowed) const {
  if (!mapping.IsMap()) return error_at(mapping, where, "expected a mapping of keys");
  for (const auto& entry : mapping) {
    // Scalar(), not as<std::string>(): a key that is a list must not throw (parse_yaml_document refuses it).
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : std::string("?");
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
    // yaml-cpp refuses 1e999 like a word; say that it is a number, only too large.
    const std::string& text = node.Scalar();
    char* end = nullptr;
    errno = 0;
    std::strtod(text.c_str(), &end);
    if (!text.empty() && end == text.c_str() + text.size() && errno == ERANGE)
      return error_at(node, key, fmt::format("expected a finite number, got '{}' (out of range)", text));
    return error_at(node, key, fmt::format("expected a number, got '{}'", text));
  }
  if (!std::isfinite(value))
    return error_at(node, key, fmt::format("expected a finite number, got '{}'", node.Scalar()));
  return value;
}

Result<double> YamlReader::required_number(const YAML::Node& parent, std::string_view key) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return error_missing(parent, key, "a number");
  if (node.IsNull()) return error_at_value(parent, key, "expected a number, got nothing");
  return number(node, key);
}

Result<std::optional<double>> YamlReader::optional_number(const YAML::Node& parent,
                                                          std::string_view key) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return std::optional<double>{};
  if (node.IsNull()) return error_at_value(parent, key, "expected a number, got nothing");
  auto value = number(node, key);
  if (!value) return value.error();
  return std::optional<double>{*value};
}

Result<std::string> YamlReader::required_string(const YAML::Node& parent, std::string_view key) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return error_missing(parent, key, "a value");
  if (!node.IsScalar()) return error_at_value(parent, key, "expected a single word");
  return node.Scalar();
}

Result<std::optional<std::string>> YamlReader::optional_string(const YAML::Node& parent,
                                                               std::string_view key) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return std::optional<std::string>{};
  if (!node.IsScalar()) {
    return error_at_value(parent, key,
                          node.IsNull() ? "expected a word or a text, got nothing"
                                        : fmt::format("expected a word or a text, not a {}",
                                                      node.IsSequence() ? "list" : "mapping"));
  }
  return std::optional<std::string>{node.Scalar()};
}

Result<std::optional<std::string>> YamlReader::optional_label(const YAML::Node& parent,
                                                              std::string_view key) const {
  auto text = optional_string(parent, key);
  if (!text || !*text) return text;
  const std::string& label = **text;
  const std::size_t bad = first_unprintable_byte(label);
  if (bad == std::string::npos) return text;
  const auto byte = static_cast<unsigned char>(label[bad]);
  // A control byte would act on the terminal that prints the name; other bytes that are not UTF-8 could not
  // go into the run's summary.json, which is UTF-8 like every JSON text.
  const bool control = byte < 0x20 || byte == 0x7F;
  return error_at_value(
      parent, key,
      fmt::format("{} (\\x{:02X}) at byte {}: a {} is one line of {}",
                  control ? "a control character" : "a byte that is not UTF-8", byte, bad + 1, key,
                  control ? "printable text" : "UTF-8 text (save the file as UTF-8)"));
}

Result<int> YamlReader::required_integer(const YAML::Node& parent, std::string_view key) const {
  auto value = required_number(parent, key);
  if (!value) return value.error();
  // Beyond int's range the cast would be undefined.
  if (std::floor(*value) != *value || std::abs(*value) > 1e9) {
    return error_at(parent[std::string(key)], key,
                    fmt::format("expected a whole number of at most 1e9 in size, got {:g}", *value));
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
    const std::string item = fmt::format("{}[{}]", key, i);
    auto v = number(node[i], item);
    if (!v) return v.error();
    if (std::abs(*v) > kMaxPointCoordinate) {
      return error_at(
          node[i], item,
          fmt::format("{:g} is too large for a coordinate (at most {:g} in size)", *v, kMaxPointCoordinate));
    }
    p[i] = *v;
  }
  return p;
}

Result<Eigen::Vector3d> YamlReader::required_point(const YAML::Node& parent, std::string_view key,
                                                   int dims) const {
  const YAML::Node node = parent[std::string(key)];
  if (!node) return error_missing(parent, key, fmt::format("a list of {} numbers", dims));
  if (node.IsNull())
    return error_at_value(parent, key, fmt::format("expected a list of {} numbers, got nothing", dims));
  return point(node, key, dims);
}

Result<std::vector<Eigen::Vector3d>> YamlReader::points(const YAML::Node& parent, std::string_view key,
                                                        int count, int dims) const {
  const YAML::Node node = parent[std::string(key)];
  const std::string what = count > 0 ? fmt::format("a list of {} points of {} numbers", count, dims)
                                     : fmt::format("a list of points of {} numbers", dims);
  if (!node) return error_missing(parent, key, what);
  if (!node.IsSequence())
    return error_at_value(
        parent, key, fmt::format("expected {}, got {}", what, node.IsNull() ? "nothing" : "a single value"));
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
  if (!node.IsSequence())
    return error_at_value(
        parent, key, fmt::format("expected {}, got {}", what, node.IsNull() ? "nothing" : "a single value"));
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
