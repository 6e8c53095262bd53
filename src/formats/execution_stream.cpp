#include "formats/execution_stream.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cstring>

namespace pkm::formats {

namespace {

// Shortest decimals that read back as the same double (std::to_chars), appended without allocation once the
// buffer has grown.
void append_number(std::string& out, double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  out.append(text, end);
}

void append_integer(std::string& out, long long value) {
  char text[24];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  out.append(text, end);
}

constexpr std::size_t kFlushBytes = 1 << 14;

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
  if (!started_) {
    buffer_ += "start";
    for (int j = 0; j < drives_; ++j) {
      buffer_ += ',';
      append_integer(buffer_, period.position[j] - period.steps[j]);
    }
    buffer_ += '\n';
    started_ = true;
  }
  buffer_ += "p,";
  append_integer(buffer_, period.line);
  for (int j = 0; j < drives_; ++j) {
    buffer_ += ',';
    append_number(buffer_, period.ideal_steps[j]);
  }
  for (int j = 0; j < drives_; ++j) {
    buffer_ += ',';
    append_integer(buffer_, period.position[j]);
  }
  buffer_ += '\n';
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
