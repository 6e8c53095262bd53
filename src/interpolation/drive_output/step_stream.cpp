#include "interpolation/drive_output/step_stream.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string_view>
#include <system_error>

namespace pkm::interpolation {

namespace {

constexpr std::string_view kStepStreamMagic = "PKMSTEP1";
constexpr std::string_view kStepStreamEndMagic = "PKMSTEND";
constexpr std::size_t kStepStreamFixedHeader = 40;  // up to the start positions
constexpr std::size_t kStepStreamEndRecord = 24;
// Writer: encoded periods go to the staged file a megabyte at a time. Reader:
// 64 KiB per read, ~9000 periods.
constexpr std::size_t kStepStreamWriteChunk = std::size_t{1} << 20;
constexpr std::size_t kStepStreamReadChunk = std::size_t{1} << 16;
// The longest record: 5 bytes per step (32 bits) and 10 for the line difference
// (64 bits).
constexpr std::size_t kStepStreamMaxRecord = 5 * kMaxActuators + 10;

constexpr std::array<std::uint32_t, 256> step_stream_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1U) ? 0xEDB88320U ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}
constexpr std::array<std::uint32_t, 256> kStepStreamCrcTable = step_stream_crc_table();

void step_stream_put(std::string& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFFU));
}

std::uint64_t step_stream_get(const std::uint8_t* in, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value |= std::uint64_t{in[i]} << (8 * i);
  return value;
}

std::uint64_t step_stream_zigzag(std::int64_t value) {
  return (static_cast<std::uint64_t>(value) << 1) ^ (value < 0 ? ~std::uint64_t{0} : std::uint64_t{0});
}

std::int64_t step_stream_unzigzag(std::uint64_t value) {
  return static_cast<std::int64_t>(value >> 1) ^ -static_cast<std::int64_t>(value & 1U);
}

void step_stream_put_varint(std::string& out, std::uint64_t value) {
  while (value >= 0x80U) {
    out.push_back(static_cast<char>((value & 0x7FU) | 0x80U));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

std::string step_stream_reason(int error_number) {
  return std::error_code(error_number, std::generic_category()).message();
}

// Reads exactly `size` bytes at `offset`; false with errno set (0 at the end of
// the file).
bool step_stream_pread(int descriptor, void* data, std::size_t size, std::uint64_t offset) {
  auto* out = static_cast<std::uint8_t*>(data);
  while (size > 0) {
    const ssize_t got = ::pread(descriptor, out, size, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      if (got == 0) errno = 0;
      return false;
    }
    out += got;
    size -= static_cast<std::size_t>(got);
    offset += static_cast<std::uint64_t>(got);
  }
  return true;
}

}  // namespace

std::string step_stream_path(const std::string& directory) {
  return (std::filesystem::path(directory) / kStepStreamName).string();
}

std::uint32_t step_stream_crc32(const void* data, std::size_t size, std::uint32_t crc) {
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = kStepStreamCrcTable[(crc ^ bytes[i]) & 0xFFU] ^ (crc >> 8);
  return ~crc;
}

// --- writer
// ---------------------------------------------------------------------------------------------

Status StepStreamWriter::open(const std::string& path, const StepStreamHeader& header) {
  auto refuse_header = [&](const std::string& why) {
    return make_error(ErrorCode::bad_input, fmt::format("cannot write {}: {}", path, why));
  };
  if (header.actuators < 1 || header.actuators > kMaxActuators)
    return refuse_header(fmt::format("{} actuators (1…{} supported)", header.actuators, kMaxActuators));
  const double period_ns = std::round(header.period_s * 1e9);
  if (!std::isfinite(header.period_s) || period_ns < 1.0 || period_ns > 1e15)
    return refuse_header(fmt::format("servo period {} s (1 ns … 10⁶ s)", header.period_s));
  if (!std::isfinite(header.step_mm) || header.step_mm <= 0.0)
    return refuse_header(fmt::format("step {} (must be positive)", header.step_mm));
  if (header.machine.size() > kStepStreamMaxMachineName)
    return refuse_header(fmt::format("machine name of {} bytes (at most {})", header.machine.size(),
                                     kStepStreamMaxMachineName));
  if (auto opened = file_.open(path); !opened) return opened;
  buffer_.reserve(kStepStreamWriteChunk + kStepStreamMaxRecord + kStepStreamEndRecord);
  buffer_.assign(kStepStreamMagic);
  step_stream_put(buffer_, kStepStreamVersion, 2);
  step_stream_put(buffer_, static_cast<std::uint64_t>(header.actuators), 2);
  step_stream_put(buffer_, 0, 4);
  step_stream_put(buffer_, static_cast<std::uint64_t>(period_ns), 8);
  step_stream_put(buffer_, std::bit_cast<std::uint64_t>(header.period_s), 8);
  step_stream_put(buffer_, std::bit_cast<std::uint64_t>(header.step_mm), 8);
  for (int j = 0; j < header.actuators; ++j)
    step_stream_put(buffer_, static_cast<std::uint64_t>(header.start_position[j]), 8);
  step_stream_put(buffer_, header.machine.size(), 4);
  buffer_ += header.machine;
  actuators_ = header.actuators;
  position_ = header.start_position;
  periods_ = 0;
  line_ = 0;
  crc_ = 0;
  open_ = true;
  return ok_status();
}

Error StepStreamWriter::refuse(const std::string& why) {
  open_ = false;
  return make_error(ErrorCode::bad_input, fmt::format("cannot write {}: {}", file_.path(), why));
}

Status StepStreamWriter::write(const StepPeriod& period) {
  if (!open_)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: the file is not open", file_.path()));
  if (period.index != periods_)
    return refuse(fmt::format("period {} given after period {} (periods must be consecutive from 0)",
                              period.index, periods_ - 1));
  for (int j = 0; j < actuators_; ++j) {
    // Unsigned: a corrupt input must give an error, not undefined behaviour.
    const auto expected = static_cast<std::int64_t>(
        static_cast<std::uint64_t>(position_[j]) + static_cast<std::uint64_t>(std::int64_t{period.steps[j]}));
    if (period.position[j] != expected)
      return refuse(
          fmt::format("period {}, actuator {}: position {} is not "
                      "the previous {} plus {} steps",
                      period.index, j + 1, period.position[j], position_[j], period.steps[j]));
  }
  for (int j = 0; j < actuators_; ++j) {
    step_stream_put_varint(buffer_, step_stream_zigzag(period.steps[j]));
    position_[j] = period.position[j];
  }
  step_stream_put_varint(buffer_, step_stream_zigzag(std::int64_t{period.line} - line_));
  line_ = period.line;
  ++periods_;
  return buffer_.size() > kStepStreamWriteChunk ? flush() : ok_status();
}

Status StepStreamWriter::flush() {
  crc_ = step_stream_crc32(buffer_.data(), buffer_.size(), crc_);
  const Status written = file_.write(buffer_);
  buffer_.clear();
  if (!written) open_ = false;
  return written;
}

Status StepStreamWriter::finish() {
  if (!open_)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: the file is not open", file_.path()));
  if (auto flushed = flush(); !flushed) return flushed;
  open_ = false;
  buffer_.assign(kStepStreamEndMagic);
  step_stream_put(buffer_, static_cast<std::uint64_t>(periods_), 8);
  step_stream_put(buffer_, crc_, 4);
  step_stream_put(buffer_, 0, 4);
  if (auto written = file_.write(buffer_); !written) return written;
  return file_.commit();
}

// --- reader
// ---------------------------------------------------------------------------------------------

StepStreamReader::~StepStreamReader() {
  close();
}

void StepStreamReader::close() {
  if (descriptor_ >= 0) ::close(descriptor_);
  descriptor_ = -1;
}

bool StepStreamReader::fail(std::uint64_t offset, const std::string& what) {
  error_ = make_error(ErrorCode::bad_input, fmt::format("{}: corrupt at byte {}: {}", path_, offset, what));
  close();
  return false;
}

namespace {

struct HeaderProblem {
  std::uint64_t offset;
  std::string what;
};

// The fixed header's fields after the magic and the version: the actuators, the flags, the servo period (in
// ns and in s, which must agree) and the step. Empty when all are sound.
std::optional<HeaderProblem> read_fixed_fields(const std::uint8_t* fixed, std::int64_t& period_ns,
                                               StepStreamHeader& header) {
  const auto actuators = step_stream_get(&fixed[10], 2);
  if (actuators < 1 || actuators > static_cast<std::uint64_t>(kMaxActuators))
    return HeaderProblem{10, fmt::format("{} actuators (1…{})", actuators, kMaxActuators)};
  if (const auto flags = step_stream_get(&fixed[12], 4); flags != 0)
    return HeaderProblem{12, fmt::format("unknown flags {:#x}", flags)};
  period_ns = static_cast<std::int64_t>(step_stream_get(&fixed[16], 8));
  header.period_s = std::bit_cast<double>(step_stream_get(&fixed[24], 8));
  header.step_mm = std::bit_cast<double>(step_stream_get(&fixed[32], 8));
  if (period_ns < 1 || period_ns > 1'000'000'000'000'000)
    return HeaderProblem{16, fmt::format("servo period {} ns", period_ns)};
  if (!std::isfinite(header.period_s) || std::abs(header.period_s * 1e9 - static_cast<double>(period_ns)) >
                                             0.5 + 1e-6 * static_cast<double>(period_ns))
    return HeaderProblem{24,
                         fmt::format("servo period {} s does not match {} ns", header.period_s, period_ns)};
  if (!std::isfinite(header.step_mm) || header.step_mm <= 0.0)
    return HeaderProblem{32, fmt::format("step {}", header.step_mm)};
  header.actuators = static_cast<int>(actuators);
  return std::nullopt;
}

// The CRC-32 of the file's bytes [0, end), read in `buffer`-sized chunks; empty on a read error (errno set).
std::optional<std::uint32_t> stream_crc32(int descriptor, std::vector<std::uint8_t>& buffer,
                                          std::uint64_t end) {
  std::uint32_t crc = 0;
  for (std::uint64_t offset = 0; offset < end;) {
    const auto chunk = static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size(), end - offset));
    if (!step_stream_pread(descriptor, buffer.data(), chunk, offset)) return std::nullopt;
    crc = step_stream_crc32(buffer.data(), chunk, crc);
    offset += chunk;
  }
  return crc;
}

}  // namespace

void StepStreamReader::reset(const std::string& path) {
  close();
  path_ = path;
  header_ = StepStreamHeader{};
  count_ = emitted_ = 0;
  line_ = 0;
  error_.reset();
  buffer_used_ = buffer_size_ = 0;
}

Status StepStreamReader::open(const std::string& path) {
  reset(path);
  auto io_error = [&](int error_number) {
    close();
    return make_error(ErrorCode::io, fmt::format("{}: cannot read the step stream: {}", path,
                                                 error_number ? step_stream_reason(error_number)
                                                              : std::string("unexpected end of file")));
  };
  auto corrupt = [&](std::uint64_t offset, const std::string& what) {
    close();
    return make_error(ErrorCode::bad_input, fmt::format("{}: corrupt at byte {}: {}", path, offset, what));
  };
  auto truncated = [&](std::uint64_t size, const std::string& what) {
    close();
    return make_error(ErrorCode::bad_input, fmt::format("{}: truncated at byte {}: {}", path, size, what));
  };
  descriptor_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor_ < 0) return io_error(errno);
  struct stat status {};
  if (::fstat(descriptor_, &status) != 0) return io_error(errno);
  if (!S_ISREG(status.st_mode)) {
    close();
    return make_error(ErrorCode::io,
                      fmt::format("{}: cannot read the step stream: not a regular file", path));
  }
  const auto size = static_cast<std::uint64_t>(status.st_size);

  std::array<std::uint8_t, kStepStreamFixedHeader> fixed{};
  if (size < kStepStreamMagic.size() ||
      !step_stream_pread(descriptor_, fixed.data(), kStepStreamMagic.size(), 0))
    return size < kStepStreamMagic.size() ? truncated(size, "not even the 8-byte magic PKMSTEP1")
                                          : io_error(errno);
  if (std::memcmp(fixed.data(), kStepStreamMagic.data(), kStepStreamMagic.size()) != 0) {
    close();
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: not a pkm step stream (no PKMSTEP1 at byte 0)", path));
  }
  if (size < kStepStreamFixedHeader)
    return truncated(size, fmt::format("the header needs at least {} bytes", kStepStreamFixedHeader));
  if (!step_stream_pread(descriptor_, fixed.data(), fixed.size(), 0)) return io_error(errno);
  const auto version = step_stream_get(&fixed[8], 2);
  if (version != kStepStreamVersion) {
    close();
    return make_error(ErrorCode::bad_input, fmt::format("{}: step stream version {} (this pkm reads {})",
                                                        path, version, kStepStreamVersion));
  }
  if (auto problem = read_fixed_fields(fixed.data(), period_ns_, header_))
    return corrupt(problem->offset, problem->what);
  const auto actuators = static_cast<std::uint64_t>(header_.actuators);

  const std::uint64_t positions_end = kStepStreamFixedHeader + 8 * actuators;
  if (size < positions_end + 4)
    return truncated(size, fmt::format("the header needs at least {} bytes", positions_end + 4));
  std::array<std::uint8_t, 8 * kMaxActuators + 4> tail{};
  if (!step_stream_pread(descriptor_, tail.data(), 8 * actuators + 4, kStepStreamFixedHeader))
    return io_error(errno);
  for (int j = 0; j < header_.actuators; ++j)
    header_.start_position[j] = static_cast<std::int64_t>(step_stream_get(&tail[8 * j], 8));
  const auto name_length = step_stream_get(&tail[8 * actuators], 4);
  if (name_length > kStepStreamMaxMachineName)
    return corrupt(positions_end, fmt::format("machine name of {} bytes (at most {})", name_length,
                                              kStepStreamMaxMachineName));
  const std::uint64_t data_begin = positions_end + 4 + name_length;
  if (size < data_begin) return truncated(size, fmt::format("the header needs {} bytes", data_begin));
  header_.machine.resize(name_length);
  if (!step_stream_pread(descriptor_, header_.machine.data(), name_length, positions_end + 4))
    return io_error(errno);

  // The end record: present only if the writer finished.
  std::array<std::uint8_t, kStepStreamEndRecord> end{};
  if (size < data_begin + kStepStreamEndRecord ||
      !step_stream_pread(descriptor_, end.data(), end.size(), size - kStepStreamEndRecord) ||
      std::memcmp(end.data(), kStepStreamEndMagic.data(), kStepStreamEndMagic.size()) != 0)
    return truncated(size,
                     "no end record (PKMSTEND): the file was cut short "
                     "or its writer did not finish");
  data_end_ = size - kStepStreamEndRecord;
  const auto count = step_stream_get(&end[8], 8);
  const auto stored_crc = static_cast<std::uint32_t>(step_stream_get(&end[16], 4));
  // Every period takes at least one byte per actuator and one for the line.
  if (count > (data_end_ - data_begin) / (actuators + 1))
    return corrupt(data_end_ + 8,
                   fmt::format("{} periods cannot fit in {} bytes", count, data_end_ - data_begin));
  if (const auto reserved = step_stream_get(&end[20], 4); reserved != 0)
    return corrupt(data_end_ + 20, fmt::format("unknown end-record field {:#x}", reserved));
  count_ = static_cast<long>(count);

  // The checksum, so that a damaged file is refused before any of it is played.
  buffer_.resize(kStepStreamReadChunk);
  const std::optional<std::uint32_t> crc = stream_crc32(descriptor_, buffer_, data_end_);
  if (!crc) return io_error(errno);
  if (*crc != stored_crc)
    return corrupt(data_end_ + 16, fmt::format("checksum {:08x} of bytes 0…{} differs from the stored {:08x}",
                                               *crc, data_end_ - 1, stored_crc));
  position_ = header_.start_position;
  buffer_offset_ = data_begin;
  return ok_status();
}

bool StepStreamReader::next_byte(std::uint8_t& byte) {
  if (buffer_used_ == buffer_size_) {
    buffer_offset_ += buffer_size_;
    buffer_used_ = buffer_size_ = 0;
    if (buffer_offset_ >= data_end_)
      return fail(data_end_, fmt::format("period {} runs into the end record", emitted_));
    const auto chunk =
        static_cast<std::size_t>(std::min<std::uint64_t>(buffer_.size(), data_end_ - buffer_offset_));
    if (!step_stream_pread(descriptor_, buffer_.data(), chunk, buffer_offset_)) {
      error_ =
          make_error(ErrorCode::io, fmt::format("{}: cannot read the step stream at byte {}: {}", path_,
                                                buffer_offset_, step_stream_reason(errno ? errno : EIO)));
      close();
      return false;
    }
    buffer_size_ = chunk;
  }
  byte = buffer_[buffer_used_++];
  return true;
}

bool StepStreamReader::read_varint(std::uint64_t& value, int max_bytes, const char* what) {
  const std::uint64_t start = buffer_offset_ + buffer_used_;
  value = 0;
  for (int i = 0; i < max_bytes; ++i) {
    std::uint8_t byte = 0;
    if (!next_byte(byte)) return false;
    value |= std::uint64_t{byte & 0x7FU} << (7 * i);
    if ((byte & 0x80U) == 0) return true;
  }
  return fail(start, fmt::format("period {}: {} longer than {} bytes", emitted_, what, max_bytes));
}

bool StepStreamReader::next(StepPeriod& period) {
  if (error_ || descriptor_ < 0) return false;
  if (emitted_ == count_) {
    const std::uint64_t at = buffer_offset_ + buffer_used_;
    if (at != data_end_)
      return fail(at, fmt::format("{} bytes after the last of the {} periods", data_end_ - at, count_));
    close();
    return false;
  }
  for (int j = 0; j < header_.actuators; ++j) {
    std::uint64_t coded = 0;
    const std::uint64_t start = buffer_offset_ + buffer_used_;
    if (!read_varint(coded, 5, "a step count")) return false;
    if (coded > std::numeric_limits<std::uint32_t>::max())
      return fail(start, fmt::format("period {}: step count out of range", emitted_));
    const std::int64_t steps = step_stream_unzigzag(coded);
    period.steps[j] = static_cast<std::int32_t>(steps);
    position_[j] = static_cast<std::int64_t>(static_cast<std::uint64_t>(position_[j]) +
                                             static_cast<std::uint64_t>(steps));
    period.position[j] = position_[j];
  }
  std::uint64_t coded = 0;
  const std::uint64_t start = buffer_offset_ + buffer_used_;
  if (!read_varint(coded, 10, "a line difference")) return false;
  // Lines are ints: a difference beyond ±2³² can only come from a damaged file (and must not overflow).
  const std::int64_t difference = step_stream_unzigzag(coded);
  const bool huge = difference > (std::int64_t{1} << 32) || difference < -(std::int64_t{1} << 32);
  const std::int64_t line = std::int64_t{line_} + (huge ? 0 : difference);
  if (huge || line < std::numeric_limits<int>::min() || line > std::numeric_limits<int>::max())
    return fail(start,
                fmt::format("period {}: program line difference {} out of range", emitted_, difference));
  line_ = static_cast<int>(line);
  period.line = line_;
  period.index = emitted_;
  period.time_s = static_cast<double>(emitted_ + 1) * header_.period_s;
  ++emitted_;
  return true;
}

}  // namespace pkm::interpolation
