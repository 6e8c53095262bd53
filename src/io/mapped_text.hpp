#pragma once
// A text file mapped into memory read-only, for a reader that goes through a long file once (a part program
// of millions of lines read while it is planned): the pages far behind and far ahead of where the reader is
// are given back to the system, which reads them again from the file if they are needed (a loop jumping
// back), so the file does not stay in memory. The text is the one read_text_input gives: without a leading
// byte-order mark; a file with lone carriage returns (old Mac line ends) is read whole and normalised
// instead.
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace pkm {

class MappedText {
 public:
  /// Errors as read_text_input's ("PATH: cannot read WHAT: REASON"); no size cap.
  static Result<std::unique_ptr<MappedText>> open(const std::string& path, std::string_view what);
  ~MappedText();
  MappedText(const MappedText&) = delete;
  MappedText& operator=(const MappedText&) = delete;

  std::string_view text() const { return text_; }
  /// Lines of the text (the last one counted even without its line feed).
  int line_count() const { return line_count_; }
  /// The byte offset of a line (1-based) or of a line a little before it.
  std::size_t offset_near_line(int line) const;
  /// The reader is at `offset`: what lies far from it goes back to the system.
  void keep_around(std::size_t offset);

 private:
  MappedText() = default;
  /// Indexes the lines; false where the text has a lone carriage return (it must be read whole).
  bool index_lines();

  void* mapping_ = nullptr;
  std::size_t mapped_bytes_ = 0;
  std::string whole_;  ///< the normalised text where the file has lone carriage returns
  std::string_view text_;
  int line_count_ = 0;
  std::vector<std::size_t> line_offsets_;  ///< of lines 1, 1 + kIndexEvery, …
};

}  // namespace pkm
