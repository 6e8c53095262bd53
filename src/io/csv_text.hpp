#pragma once
// The pieces every CSV reader shares (measurement, fixture and load files, the drive steps, a run's files
// read back for the report): lines with their numbers, fields with their columns, `# key: value` header
// lines, numbers that must be finite and of a sane size, and errors that name "FILE:LINE:COLUMN: KEY: reason"
// with the place also as ErrorLocation fields.
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "io/text_lines.hpp"

namespace pkm::csv_text {

/// Largest magnitude of any number in a calibration file: 1 km in mm (or 10⁶ degrees). A value beyond it is a
/// typing error or a unit mix-up, and would wreck the identification's conditioning if taken.
inline constexpr double kMaxMagnitude = 1e6;

/// The text split into lines, each with its 1-based number (io/text_lines.hpp, with CR LF ends accepted; an
/// empty text is one empty line, as an editor shows it).
class Lines {
 public:
  explicit Lines(std::string_view text) : walker_(text), empty_(text.empty()) {}
  /// The next line (without its end), false at the end of the text.
  bool next(std::string_view& line);
  int number() const { return number_; }

 private:
  TextLines walker_;
  bool empty_;
  int number_ = 0;
};

/// The fields of a comma-separated row one at a time, as they stand (no quoting, no trimming), without
/// allocating: the one splitter of the CSV readers.
class Fields {
 public:
  explicit Fields(std::string_view row) : row_(row) {}
  /// The next field, false after the last (a row has at least one field, maybe empty).
  bool next(std::string_view& field) {
    if (done_) return false;
    start_ = at_;
    const std::size_t comma = row_.find(',', at_);
    done_ = comma == std::string_view::npos;
    field = row_.substr(at_, done_ ? std::string_view::npos : comma - at_);
    at_ = done_ ? row_.size() : comma + 1;
    return true;
  }
  /// The 0-based offset in the row of the field returned last.
  std::size_t offset() const { return start_; }

 private:
  std::string_view row_;
  std::size_t at_ = 0, start_ = 0;
  bool done_ = false;
};

struct Field {
  std::string_view text;  ///< without surrounding blanks
  int column = 1;  ///< 1-based character column of its first character (of the comma's follower if empty)
};

/// The fields of a comma-separated row (no quoting: names in these files never hold commas).
std::vector<Field> split_row(std::string_view row);
std::string_view trim(std::string_view text);
/// True for a line that holds nothing or only blanks.
bool is_blank(std::string_view line);

/// A `# key: value` header line: key of letters, digits and '_', value trimmed.
struct Directive {
  std::string_view key;
  std::string_view value;
  int key_column = 0;
  int value_column = 0;
};
/// The directive of a comment line, false for a free comment (or not a comment).
bool directive(std::string_view line, Directive& out);

/// "FILE:LINE:COLUMN: KEY: message", ErrorCode::bad_input, with the location as fields.
Error error_at(const std::string& source, int line, int column, std::string_view key,
               std::string_view message);

/// A finite number of magnitude at most kMaxMagnitude; `unit` is for the message ("mm").
Result<double> number(const std::string& source, int line, const Field& field, std::string_view key,
                      std::string_view unit);

}  // namespace pkm::csv_text
