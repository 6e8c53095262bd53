#include "report/csv_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "io/csv_text.hpp"
#include "io/input_file.hpp"

namespace pkm::report {

Status CsvReader::open(const std::string& path) {
  path_ = path;
  // A directory or a device in place of the CSV is refused by name; a missing file gets the hint below.
  if (std::error_code ignored; std::filesystem::exists(path, ignored)) {
    if (auto checked = check_input_file(path, "run data", InputReading::streamed); !checked) return checked;
  }
  in_.open(path, std::ios::binary);
  if (!in_)
    return make_error(ErrorCode::io, fmt::format("{}: cannot open (is this a pkm run directory?)", path));
  if (!std::getline(in_, text_)) return make_error(ErrorCode::bad_input, fmt::format("{}: empty file", path));
  line_ = 1;
  if (!text_.empty() && text_.back() == '\r') text_.pop_back();
  csv_text::Fields header(text_);
  for (std::string_view column; header.next(column);) columns_.emplace_back(column);
  return ok_status();
}

int CsvReader::column(std::string_view name) const {
  const auto it = std::find(columns_.begin(), columns_.end(), name);
  return it == columns_.end() ? -1 : static_cast<int>(it - columns_.begin());
}

Result<int> CsvReader::require(std::string_view name) const {
  const int index = column(name);
  if (index < 0) {
    return make_error(ErrorCode::bad_input, fmt::format("{}:1: no column '{}'", path_, name));
  }
  return index;
}

bool CsvReader::next(std::vector<double>& row) {
  do {  // empty lines (a trailing one) are skipped
    if (error_ || !std::getline(in_, text_)) return false;
    ++line_;
    if (!text_.empty() && text_.back() == '\r') text_.pop_back();
  } while (text_.empty());
  row.assign(columns_.size(), std::numeric_limits<double>::quiet_NaN());
  csv_text::Fields fields(text_);
  std::string_view field;
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    if (!fields.next(field)) {
      error_ = Error{ErrorCode::bad_input,
                     fmt::format("{}:{}: {} of {} columns", path_, line_, k, columns_.size())};
      return false;
    }
    if (field.empty()) continue;
    double value = 0.0;
    const auto [stop, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (ec != std::errc() || stop != field.data() + field.size()) {
      error_ = Error{ErrorCode::bad_input,
                     fmt::format("{}:{}: {}: '{}' is not a number", path_, line_, columns_[k], field)};
      return false;
    }
    row[k] = value;
  }
  if (fields.next(field)) {
    error_ = Error{ErrorCode::bad_input,
                   fmt::format("{}:{}: more than the header's {} columns", path_, line_, columns_.size())};
    return false;
  }
  return true;
}

Result<bool> next_in_step(CsvReader& a, std::vector<double>& row_a, CsvReader& b,
                          std::vector<double>& row_b) {
  const bool more_a = a.next(row_a);
  const bool more_b = b.next(row_b);
  if (a.error()) return *a.error();
  if (b.error()) return *b.error();
  if (more_a != more_b) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{} and {} have different numbers of rows (from line {})", a.path(),
                                  b.path(), std::min(a.line(), b.line()) + 1));
  }
  return more_a;
}

Result<long> count_csv_rows(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return make_error(ErrorCode::io, fmt::format("{}: cannot open", path));
  std::vector<char> buffer(std::size_t{1} << 20);
  long lines = 0;
  char last = '\n';
  while (const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), file)) {
    lines += std::count(buffer.data(), buffer.data() + got, '\n');
    last = buffer[got - 1];
  }
  std::fclose(file);
  if (last != '\n') ++lines;  // a last line without its newline
  return std::max(0L, lines - 1);
}

}  // namespace pkm::report
