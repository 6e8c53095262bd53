#pragma once
// Drive steps as a compact binary stream (steps.bin): about one byte per
// actuator and period, so that a long run at 10 kHz stays small and the
// real-time player (realtime_player.hpp) decodes it in nanoseconds.
// docs/step-stream.md has the same description with an example.
//
// Layout, all integers little-endian, doubles IEEE 754 binary64 little-endian:
//   offset      size  field
//   0           8     magic "PKMSTEP1"
//   8           2     u16 format version, 1
//   10          2     u16 actuator count n, 1…6
//   12          4     u32 flags, 0 (reserved)
//   16          8     u64 servo period h in nanoseconds (what the player times
//   with) 24          8     f64 servo period h in seconds (exact; the period
//   times are (k + 1)·h from it) 32          8     f64 step: mm per step (rad
//   per step for angular actuators) 40          8·n   i64 position codes before
//   the first period, in steps 40+8n       4     u32 length L of the machine
//   file name (≤ 4096) 44+8n       L     the machine file name, UTF-8, no
//   terminator 44+8n+L     …     one record per period:
//                       n × steps of actuator j in the period, zig-zag LEB128
//                       (one byte when |steps| < 64) 1 × program line minus the
//                       previous period's line (0 before the first), zig-zag
//                       LEB128
//   size−24     24    end record, written by finish():
//                       "PKMSTEND", u64 period count, u32 CRC-32 (IEEE, as
//                       zlib) of every byte before the end record, u32 0
//                       (reserved)
// Zig-zag maps 0, −1, 1, −2, … to 0, 1, 2, 3, …; LEB128 then stores 7 bits per
// byte, low bits first, the high bit set on every byte but the last.
//
// Not stored, because they follow from the rest: the period number (records are
// consecutive from 0), the period's end time (k + 1)·h, and the position codes
// (start + the running sum of the steps). The writer checks that the periods it
// is given agree with that, so the file always reads back exactly as written.
//
// The count lives in an end record rather than in the header because the file
// is written front to back through a staged file (io/atomic_file.hpp), which
// cannot seek. The end record also tells a finished file from one cut short:
// the reader checks it and the checksum in open(), before anything is played.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "interpolation/quantisation/step_period.hpp"
#include "io/atomic_file.hpp"

namespace pkm::interpolation {

inline constexpr const char* kStepStreamName = "steps.bin";
inline constexpr std::uint16_t kStepStreamVersion = 1;
inline constexpr std::uint32_t kStepStreamMaxMachineName = 4096;

/// DIRECTORY/steps.bin.
std::string step_stream_path(const std::string& directory);

/// CRC-32 (IEEE 802.3 polynomial, the value zlib's crc32 gives) of `size`
/// bytes, continuing `crc`.
std::uint32_t step_stream_crc32(const void* data, std::size_t size, std::uint32_t crc = 0);

class StepStreamWriter : public StepSink {
 public:
  /// Stages the file `path` (usually step_stream_path(dir)) and writes the
  /// header. Errors: an actuator count outside 1…6, a period or step that is
  /// not positive, a machine name longer than 4096 bytes, io.
  Status open(const std::string& path, const StepStreamHeader& header);
  /// Appends one period. Its index must be the next one, and each position code
  /// the previous one (or the start position) plus the period's steps.
  /// Buffered; no allocation.
  Status write(const StepPeriod& period) override;
  /// Writes the end record and renames the file into place. Without it the file
  /// never appears.
  Status finish() override;

  long periods() const { return periods_; }

 private:
  Status flush();
  Error refuse(const std::string& why);  // closes the writer: a stream with a
                                         // gap must not be finished

  StagedFile file_;
  std::string buffer_;
  int actuators_ = 0;
  long periods_ = 0;
  int line_ = 0;
  std::array<std::int64_t, kMaxActuators> position_{};
  std::uint32_t crc_ = 0;
  bool open_ = false;
};

class StepStreamReader {
 public:
  StepStreamReader() = default;
  ~StepStreamReader();
  StepStreamReader(const StepStreamReader&) = delete;
  StepStreamReader& operator=(const StepStreamReader&) = delete;

  /// Opens a steps.bin and checks its header, its end record and its checksum,
  /// reading the file once. Errors name the file and, for a truncated or
  /// corrupt file, the byte offset.
  Status open(const std::string& path);

  const StepStreamHeader& header() const { return header_; }
  /// The servo period as stored for timing, ns.
  std::int64_t period_ns() const { return period_ns_; }
  /// Periods in the file (from the end record).
  long period_count() const { return count_; }
  const std::string& path() const { return path_; }

  /// The next period, with its index, time (k + 1)·h, line and position codes
  /// recomputed. False after the last period or on a decoding error (error()
  /// then says which byte). No allocation.
  bool next(StepPeriod& period);
  const std::optional<Error>& error() const { return error_; }

 private:
  bool next_byte(std::uint8_t& byte);
  bool read_varint(std::uint64_t& value, int max_bytes, const char* what);
  bool fail(std::uint64_t offset, const std::string& what);
  void close();
  /// Closes and forgets the previous file: the reader as new, for `path`.
  void reset(const std::string& path);

  std::string path_;
  StepStreamHeader header_;
  std::int64_t period_ns_ = 0;
  long count_ = 0;
  long emitted_ = 0;
  int line_ = 0;
  std::array<std::int64_t, kMaxActuators> position_{};
  int descriptor_ = -1;
  std::vector<std::uint8_t> buffer_;
  std::size_t buffer_used_ = 0, buffer_size_ = 0;
  std::uint64_t buffer_offset_ = 0;  // file offset of buffer_[0]
  std::uint64_t data_end_ = 0;       // file offset of the end record
  std::optional<Error> error_;
};

}  // namespace pkm::interpolation
