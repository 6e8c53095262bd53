#pragma once
// Walking a text line by line with 1-based line numbers, without copying: the one line walker (G-code
// blocks, tool-table rows, the CSV readers through io/csv_text.hpp, the steps files).
#include <string_view>

namespace pkm {

class TextLines {
 public:
  explicit TextLines(std::string_view text) : text_(text) {}
  /// The next line (without its '\n') and its number; false at the end of the text.
  bool next(std::string_view& line, int& number) {
    if (begin_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', begin_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(begin_, end - begin_);
    begin_ = end + 1;
    number = ++number_;
    return true;
  }

 private:
  std::string_view text_;
  std::size_t begin_ = 0;
  int number_ = 0;
};

}  // namespace pkm
