#pragma once
// What pkm refuses in a YAML text before yaml-cpp builds its node tree, found from the parser's events:
// - an alias inside the node it names (`name: &r [*r]`): the tree would be a cycle, and every reader that
//   walks it would recurse until the stack overflows;
// - aliases that expand to more than kMaxYamlAliasNodes nodes ("billion laughs": nine anchors of nine
//   aliases each are 387 million nodes to walk from a 200-byte file);
// - a second document (`---`): YAML::Load reads only the first and would drop the rest without a word;
// - a quoted text that does not end on the line where it starts: the quote is most likely unclosed, and
//   yaml-cpp would read on to the next quote (dozens of lines away) and blame that place, or to the end of
//   the file without any error.
// Each is an Error "FILE:LINE:COLUMN: WHAT: reason" at the alias, the document or the quote.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace YAML {
class Exception;
}

namespace pkm {

/// The most nodes that aliases may add to a document when expanded (every walk of the tree visits them).
/// pkm's own files use no aliases at all; a hand-written file that shares a few points stays far below.
inline constexpr std::uint64_t kMaxYamlAliasNodes = 100000;

/// The checks above on `text`. yaml-cpp exceptions are not caught here: parse_yaml_document reports them,
/// and if one is thrown after a problem was found, `found` holds that problem (the better message).
class YamlStreamCheck {
 public:
  YamlStreamCheck(std::string_view text, std::string source_name);
  /// Runs yaml-cpp's parser over every document of the text; may throw YAML::Exception.
  void run();
  /// The first problem seen, if any (also when run() threw afterwards).
  const std::optional<Error>& found() const { return found_; }
  /// After run() threw `e`: the cause where yaml-cpp's own place is not where the mistake is, if it is one
  /// of these: found(); a [ or { never closed (yaml-cpp says so at the end of the file, not at the bracket);
  /// a TAB in the indentation of the line yaml-cpp stopped on or the one before (yaml-cpp's "illegal map
  /// value" or "end of map not found" further on).
  std::optional<Error> explain(const YAML::Exception& e) const;

 private:
  friend class YamlStreamEvents;
  struct OpenFlow {
    int line;  // 1-based
    int column;
    char bracket;
  };
  Error located(int line, int column, const std::string& what, const std::string& reason) const;
  std::optional<Error> tab_indentation(int error_line) const;

  std::string_view text_;
  std::string source_;
  std::optional<Error> found_;
  std::vector<OpenFlow> open_flows_;  // the [ and { open at the current event
};

}  // namespace pkm
