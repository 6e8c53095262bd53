#include "formats/execution_stream.hpp"

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <cstring>

namespace pkm::formats {

namespace {

constexpr std::size_t kFlushBytes = 1 << 14;
// The widest record: "p," + a line + 6 shortest doubles + 6 integers, each with its comma.
using RecordBuffer = std::array<char, 512>;

}  // namespace

Status ExecutionStreamWriter::open(const std::string& target, const std::string& machine, int drives,
                                   double period_s, double step) {
  drives_ = drives;
  to_stdout_ = target == "-";
  if (!to_stdout_) {
    if (Status opened = file_.open(target); !opened) return opened;
  }
  buffer_.reserve(2 * kFlushBytes);
  buffer_ = fmt::format("# pkm execution stream 1: {}, {} drives, period {} s, step {}\n", machine, drives,
                        period_s, step);
  return ok_status();
}

Status ExecutionStreamWriter::put(std::string_view text) {
  if (!to_stdout_) return file_.write(text);
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
    return make_error(ErrorCode::io,
                      fmt::format("cannot write the execution stream: {}", std::strerror(errno)));
  return ok_status();
}

Status ExecutionStreamWriter::write(const interpolation::StepPeriod& period) {
  RecordBuffer record;
  char* out = record.data();
  if (!started_) {  // the drives' positions before the first period
    out = fmt::format_to(out, "start");
    for (int j = 0; j < drives_; ++j) out = fmt::format_to(out, ",{}", period.position[j] - period.steps[j]);
    *out++ = '\n';
    started_ = true;
  }
  out = fmt::format_to(out, "p,{}", period.line);
  for (int j = 0; j < drives_; ++j) out = fmt::format_to(out, ",{}", period.ideal_steps[j]);
  for (int j = 0; j < drives_; ++j) out = fmt::format_to(out, ",{}", period.position[j]);
  *out++ = '\n';
  buffer_.append(record.data(), static_cast<std::size_t>(out - record.data()));
  if (buffer_.size() < kFlushBytes) return ok_status();
  Status written = put(buffer_);
  buffer_.clear();
  return written;
}

Status ExecutionStreamWriter::finish() {
  buffer_ += "end\n";
  Status written = put(buffer_);
  buffer_.clear();
  if (!written) return written;
  return to_stdout_ ? ok_status() : file_.commit();
}

}  // namespace pkm::formats
