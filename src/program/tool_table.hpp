#pragma once
// A LinuxCNC-format tool table, for G43 tool length offsets. One tool per line:
//   T1 P1 Z25.0 D6 ;comment
// T tool number, P pocket, Z length offset (mm), D diameter (mm); `;` starts a comment. Offsets along other
// axes (X Y A B C U V W) and lathe data (I J Q) are accepted only when zero: pkm applies length along Z only.
// Values are millimetres (LinuxCNC reads the table in the machine's units; see docs/part-programs.md).
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/result.hpp"

namespace pkm::program {

struct ToolEntry {
  int tool = 0;
  int pocket = 0;
  double length_mm = 0.0;
  double diameter_mm = 0.0;
  int line = 0;  ///< where it was defined
};

class ToolTable {
 public:
  ToolTable() = default;
  explicit ToolTable(std::vector<ToolEntry> entries) : entries_(std::move(entries)) {}

  /// The entry for a tool number, or nullptr.
  const ToolEntry* find(int tool) const;
  const std::vector<ToolEntry>& entries() const { return entries_; }
  /// Adds the entry, or replaces the one with its tool number (G10 L1/L10/L11).
  void set(const ToolEntry& entry);

 private:
  std::vector<ToolEntry> entries_;
};

/// Parses a tool table; errors name "SOURCE:LINE:COL".
Result<ToolTable> parse_tool_table(std::string_view text, const std::string& source_name);

/// Reads and parses a tool table file (error code io when it cannot be read).
Result<ToolTable> read_tool_table(const std::string& path);

}  // namespace pkm::program
