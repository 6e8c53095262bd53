#include "io/spif_profile_file.hpp"

#include "io/csv_text.hpp"
#include "io/text_file.hpp"

namespace pkm {

Result<std::vector<std::array<double, 2>>> parse_spif_profile(std::string_view text,
                                                              const std::string& source) {
  csv_text::Lines lines(text);
  std::string_view line;
  bool header = false;
  std::vector<std::array<double, 2>> rows;
  while (lines.next(line)) {
    if (csv_text::is_blank(line) || csv_text::trim(line).front() == '#') continue;
    const std::vector<csv_text::Field> fields = csv_text::split_row(line);
    if (!header) {
      if (fields.size() != 2 || fields[0].text != "depth_mm" || fields[1].text != "radius_mm")
        return csv_text::error_at(source, lines.number(), 1, "header",
                                  "expected the columns depth_mm,radius_mm");
      header = true;
      continue;
    }
    if (fields.size() != 2) {
      return csv_text::error_at(source, lines.number(), 1, "row", "expected two values: depth_mm,radius_mm");
    }
    auto depth = csv_text::number(source, lines.number(), fields[0], "depth_mm", "mm");
    if (!depth) return depth.error();
    auto radius = csv_text::number(source, lines.number(), fields[1], "radius_mm", "mm");
    if (!radius) return radius.error();
    if (rows.empty() ? *depth != 0.0 : !(*depth > rows.back()[0])) {
      return csv_text::error_at(source, lines.number(), fields[0].column, "depth_mm",
                                rows.empty() ? "the first row must be at depth 0 (the first plane)"
                                             : "depths must increase from row to row");
    }
    if (!(*radius > 0.0))
      return csv_text::error_at(source, lines.number(), fields[1].column, "radius_mm", "must be positive");
    rows.push_back({*depth, *radius});
  }
  if (rows.size() < 2) {
    return csv_text::error_at(source, lines.number(), 1, "rows",
                              "the profile needs at least two rows (depth 0 and the deepest)");
  }
  return rows;
}

Result<std::vector<std::array<double, 2>>> read_spif_profile(const std::string& path) {
  auto text = read_text_file(path, "profile");
  if (!text) return text.error();
  return parse_spif_profile(*text, path);
}

}  // namespace pkm
