#include "program/tool_table.hpp"

#include <fmt/format.h>

#include <cmath>

#include "io/text_file.hpp"
#include "io/text_lines.hpp"
#include "program/gcode_lexer.hpp"

namespace pkm::program {

const ToolEntry* ToolTable::find(int tool) const {
  for (const ToolEntry& entry : entries_)
    if (entry.tool == tool) return &entry;
  return nullptr;
}

void ToolTable::set(const ToolEntry& entry) {
  for (ToolEntry& existing : entries_) {
    if (existing.tool == entry.tool) {
      existing = entry;
      return;
    }
  }
  entries_.push_back(entry);
}

namespace {

// A tool or pocket number: whole, >= 0 and small enough for an int.
bool is_number(double value) {
  return value >= 0.0 && value <= 1e6 && std::abs(value - std::round(value)) < 1e-9;
}

}  // namespace

Result<ToolTable> parse_tool_table(std::string_view text, const std::string& source_name) {
  std::vector<ToolEntry> entries;
  gcode::LexedLine lexed;
  int line_number = 0;
  std::string_view line;
  TextLines lines(text);
  while (lines.next(line, line_number)) {
    const gcode::LineRef where{source_name, line_number};
    if (auto lexing = gcode::lex_line(line, where, lexed); !lexing) return lexing.error();
    if (lexed.block_delete || lexed.percent) return gcode::error_at(where, 1, "not a tool table line");
    if (lexed.words.empty()) continue;
    ToolEntry entry;
    entry.line = line_number;
    bool has_tool = false;
    for (const gcode::Word& word : lexed.words) {
      switch (word.letter) {
        case 'T':
          if (!is_number(word.value))
            return gcode::error_at(where, word.column,
                                   "tool number T must be a whole number from 0 to 1000000");
          entry.tool = static_cast<int>(std::lround(word.value));
          has_tool = true;
          break;
        case 'P':
          if (!is_number(word.value))
            return gcode::error_at(where, word.column, "pocket P must be a whole number from 0 to 1000000");
          entry.pocket = static_cast<int>(std::lround(word.value));
          break;
        case 'Z':
          entry.length_mm = word.value;
          break;
        case 'D':
          entry.diameter_mm = word.value;
          break;
        case 'X':
        case 'Y':
        case 'A':
        case 'B':
        case 'C':
        case 'U':
        case 'V':
        case 'W':
        case 'I':
        case 'J':
        case 'Q':
          // Offsets along other axes would move the tool point sideways; pkm applies the length along Z only.
          if (word.value != 0.0)
            return gcode::error_at(
                where, word.column,
                fmt::format("{} offset is not supported (only Z tool lengths)", word.letter));
          break;
        default:
          return gcode::error_at(where, word.column, fmt::format("unknown tool table word {}", word.letter));
      }
    }
    if (!has_tool)
      return gcode::error_at(where, lexed.words.front().column, "tool table line without a T word");
    for (const ToolEntry& other : entries)
      if (other.tool == entry.tool)
        return gcode::error_at(
            where, lexed.words.front().column,
            fmt::format("tool T{} defined again (first on line {})", entry.tool, other.line));
    entries.push_back(entry);
  }
  return ToolTable(std::move(entries));
}

Result<ToolTable> read_tool_table(const std::string& path) {
  auto text = read_text_file(path, "tool table");
  if (!text) return text.error();
  return parse_tool_table(*text, path);
}

}  // namespace pkm::program
