#include "interpolation/drive_output/steps_csv.hpp"

#include <fmt/format.h>

#include <charconv>
#include <filesystem>
#include <iterator>
#include <system_error>

#include "io/csv_text.hpp"
#include "io/text_file.hpp"
#include "io/text_lines.hpp"

namespace pkm::interpolation {

namespace {

// Rows gather in memory and go to the staged file a megabyte at a time: one
// write per period would cost a system call each at 10 kHz.
constexpr std::size_t kStepsCsvChunk = std::size_t{1} << 20;

// The widest row: 20 + 24 (shortest double) + 11 + 6·11 + 6·20 characters and
// 16 separators.
static_assert(std::tuple_size_v<StepRowBuffer> >= 20 + 24 + 11 + kMaxActuators * (11 + 20) + 16);

template <class T>
bool steps_csv_parse(std::string_view field, T& value) {
  const char* end = field.data() + field.size();
  const auto [stop, error] = std::from_chars(field.data(), end, value);
  return error == std::errc() && stop == end;
}

// Splits `line` at commas into `fields`; false if there are more than
// fields.size().
template <std::size_t N>
bool steps_csv_split(std::string_view line, std::array<std::string_view, N>& fields, std::size_t& count) {
  count = 0;
  csv_text::Fields cursor(line);
  for (std::string_view field; cursor.next(field);) {
    if (count == N) return false;
    fields[count++] = field;
  }
  return true;
}

}  // namespace

std::string steps_csv_path(const std::string& directory) {
  return (std::filesystem::path(directory) / kStepsCsvName).string();
}

std::string steps_csv_header(int actuators) {
  std::string header = "period,time_s,line";
  for (int j = 1; j <= actuators; ++j) header += fmt::format(",steps_{}", j);
  for (int j = 1; j <= actuators; ++j) header += fmt::format(",position_{}", j);
  header += '\n';
  return header;
}

std::string_view format_step_row(const StepPeriod& period, int actuators, StepRowBuffer& buffer) {
  char* out = fmt::format_to(buffer.data(), "{},{},{}", period.index, period.time_s, period.line);
  for (int j = 0; j < actuators; ++j) out = fmt::format_to(out, ",{}", period.steps[j]);
  for (int j = 0; j < actuators; ++j) out = fmt::format_to(out, ",{}", period.position[j]);
  *out++ = '\n';
  return {buffer.data(), static_cast<std::size_t>(out - buffer.data())};
}

Status StepsCsvWriter::open(const std::string& path, const StepStreamHeader& header) {
  if (header.actuators < 1 || header.actuators > kMaxActuators)
    return make_error(ErrorCode::bad_input, fmt::format("cannot write {}: {} actuators (1…{} supported)",
                                                        path, header.actuators, kMaxActuators));
  if (auto opened = file_.open(path); !opened) return opened;
  actuators_ = header.actuators;
  buffer_.reserve(kStepsCsvChunk + std::tuple_size_v<StepRowBuffer>);
  buffer_ = steps_csv_header(actuators_);
  open_ = true;
  return ok_status();
}

Status StepsCsvWriter::write(const StepPeriod& period) {
  if (!open_)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: the file is not open", file_.path()));
  StepRowBuffer row;
  buffer_.append(format_step_row(period, actuators_, row));
  return buffer_.size() > kStepsCsvChunk ? flush() : ok_status();
}

Status StepsCsvWriter::flush() {
  const Status written = file_.write(buffer_);
  buffer_.clear();
  if (!written) open_ = false;
  return written;
}

Status StepsCsvWriter::finish() {
  if (!open_)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: the file is not open", file_.path()));
  open_ = false;
  if (auto flushed = flush(); !flushed) return flushed;
  return file_.commit();
}

Result<StepsCsv> read_steps_csv(const std::string& path) {
  auto text = read_text_file(path, "the steps file");
  if (!text) return text.error();
  return parse_steps_csv(*text, path);
}

Result<StepsCsv> parse_steps_csv(std::string_view text, const std::string& path) {
  TextLines lines(text);
  std::string_view line;
  int number = 0;
  auto fail = [&](const std::string& what) {
    return make_error(ErrorCode::bad_input, fmt::format("{}:{}: {}", path, number, what));
  };
  constexpr std::size_t kMaxFields = 3 + 2 * kMaxActuators;
  std::array<std::string_view, kMaxFields> fields;
  std::size_t count = 0;
  if (!lines.next(line, number)) return fail("empty file, expected the header " + steps_csv_header(1));
  if (!steps_csv_split(line, fields, count) || count < 5 || (count - 3) % 2 != 0)
    return fail(
        fmt::format("expected the header "
                    "period,time_s,line,steps_1..n,position_1..n (n ≤ {})",
                    kMaxActuators));
  StepsCsv table;
  table.actuators = static_cast<int>((count - 3) / 2);
  if (std::string expected = steps_csv_header(table.actuators); std::string(line) + '\n' != expected)
    return fail("expected the header " + expected.substr(0, expected.size() - 1));
  const auto n = static_cast<std::size_t>(table.actuators);
  while (lines.next(line, number)) {
    if (line.empty()) continue;
    StepPeriod period;
    if (!steps_csv_split(line, fields, count) || count != 3 + 2 * n)
      return fail(fmt::format("expected {} fields", 3 + 2 * n));
    bool parsed = steps_csv_parse(fields[0], period.index) && steps_csv_parse(fields[1], period.time_s) &&
                  steps_csv_parse(fields[2], period.line);
    for (std::size_t j = 0; j < n && parsed; ++j)
      parsed = steps_csv_parse(fields[3 + j], period.steps[j]) &&
               steps_csv_parse(fields[3 + n + j], period.position[j]);
    if (!parsed) return fail("expected integers, and a number for time_s");
    table.periods.push_back(period);
  }
  return table;
}

}  // namespace pkm::interpolation
