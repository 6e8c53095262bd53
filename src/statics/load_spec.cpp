// The CLI's --load text: "key=value,key=value" for one load case, or "@FILE" for a load file (YAML, or CSV
// per program line when FILE ends in .csv).
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <vector>

#include "io/input_file.hpp"
#include "statics/load_keys.hpp"
#include "statics/load_model.hpp"

namespace pkm::statics {
namespace {

std::string_view load_spec_trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> load_spec_split(std::string_view s, char separator) {
  std::vector<std::string_view> parts;
  for (;;) {
    const std::size_t at = s.find(separator);
    parts.push_back(s.substr(0, at));
    if (at == std::string_view::npos) return parts;
    s.remove_prefix(at + 1);
  }
}

Error load_spec_error(std::string_view item, std::string_view message) {
  return make_error(ErrorCode::bad_input, fmt::format("'{}': {}", item, message));
}

// The whole text must be one finite number ("1e3", "-5", "+2.5").
std::optional<double> load_spec_number(std::string_view text) {
  text = load_spec_trim(text);
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// Why load_spec_number refused `text`: "1e999" and "nan" are numbers, only not usable ones.
std::string load_spec_number_problem(std::string_view key, std::string_view text) {
  text = load_spec_trim(text);
  double value = 0.0;
  std::string_view digits = text.size() > 1 && text.front() == '+' ? text.substr(1) : text;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (!digits.empty() && end == digits.data() + digits.size()) {
    if (ec == std::errc::result_out_of_range)
      return fmt::format("{}: '{}' is out of range for a number", key, text);
    if (ec == std::errc() && !std::isfinite(value))
      return fmt::format("{}: expected a finite number, got '{}'", key, text);
  }
  return fmt::format("{}: expected a number, got '{}'", key, text);
}

Status load_spec_item(std::string_view item, CuttingLoad& load) {
  const std::size_t eq = item.find('=');
  if (eq == std::string_view::npos) {
    return load_spec_error(item, fmt::format("expected key=value (keys: {})", load_key_list()));
  }
  const std::string_view key = load_spec_trim(item.substr(0, eq));
  const std::string_view value = load_spec_trim(item.substr(eq + 1));
  if (double* field = load_number_field(load, key)) {
    const auto v = load_spec_number(value);
    if (!v) return load_spec_error(item, load_spec_number_problem(key, value));
    if (auto problem = load_number_problem(key, *v)) return load_spec_error(item, *problem);
    *field = *v;
    return ok_status();
  }
  if (Eigen::Vector3d* field = load_vector_field(load, key)) {
    const auto parts = load_spec_split(value, ':');
    if (parts.size() != 3) {
      return load_spec_error(item, fmt::format("{}: expected three numbers X:Y:Z, got '{}'", key, value));
    }
    for (int i = 0; i < 3; ++i) {
      const auto v = load_spec_number(parts[i]);
      if (!v) return load_spec_error(item, load_spec_number_problem(key, parts[i]));
      if (auto problem = load_number_problem(key, *v)) return load_spec_error(item, *problem);
      (*field)[i] = *v;
    }
    return ok_status();
  }
  if (key == "contact") {
    const auto side = contact_side_from_word(value);
    if (!side) return load_spec_error(item, fmt::format("contact: expected left or right, got '{}'", value));
    load.contact_side = *side;
    return ok_status();
  }
  return load_spec_error(item, fmt::format("unknown key '{}' (keys: {})", key, load_key_list()));
}

Result<LoadModel> load_spec_file(const std::string& path) {
  if (path.empty()) return make_error(ErrorCode::bad_input, "'@' must be followed by a file name");
  auto text = read_text_input(path, "load file");
  if (!text) return text.error();
  if (path.size() >= 4 && path.compare(path.size() - 4, 4, ".csv") == 0) return parse_load_csv(*text, path);
  return parse_load_yaml(*text, path);
}

}  // namespace

Result<LoadModel> parse_load_spec(std::string_view spec) {
  spec = load_spec_trim(spec);
  if (!spec.empty() && spec.front() == '@') return load_spec_file(std::string(spec.substr(1)));
  if (spec.empty()) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("empty; expected key=value pairs ({}) or @FILE", load_key_list()));
  }
  LoadModel model;
  std::vector<std::string_view> seen;
  for (std::string_view raw : load_spec_split(spec, ',')) {
    const std::string_view item = load_spec_trim(raw);
    if (item.empty()) return load_spec_error(spec, "empty item between commas");
    const std::string_view key = load_spec_trim(item.substr(0, item.find('=')));
    for (std::string_view s : seen) {
      // A repeated key is most likely a typo for another one; do not let the last silently win.
      if (s == key) return load_spec_error(item, fmt::format("{} is given twice", key));
    }
    if (auto ok = load_spec_item(item, model.default_load); !ok) return ok.error();
    seen.push_back(key);
  }
  return model;
}

}  // namespace pkm::statics
