#pragma once
// The library entry points the fuzz harnesses drive, one per input format, shared with the regression test
// (tests/program/fuzz_regressions_test.cpp) so that a reproducer replays exactly as it was found. Each takes
// the raw bytes and returns whether the library accepted them; bad input must come back as an error, so
// nothing here catches an exception.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "interpolation/drive_output/step_stream.hpp"
#include "interpolation/drive_output/steps_csv.hpp"
#include "io/machine_file.hpp"
#include "program/part_program.hpp"
#include "statics/load_model.hpp"

namespace pkm::fuzz {

/// `pkm interpret/plan prog.ngc`: the G-code interpreter on the file's text.
/// Loops are bounded lower than pkm's default so that a program that loops for ever is refused within the
/// fuzzer's time limit (the bound is what is tested, not its size).
inline bool run_gcode(std::string_view bytes) {
  pkm::program::InterpretOptions options;
  options.max_blocks = 200'000;
  return pkm::program::interpret_gcode(bytes, "fuzz.ngc", options).ok();
}

/// `pkm plan prog.cl`: the APT CL-data reader on the file's text.
inline bool run_cl(std::string_view bytes) {
  return pkm::program::read_cl_data(bytes, "fuzz.cl").ok();
}

/// `--machine FILE.yaml`: load_machine_file reads the file and parses its text here.
inline bool run_machine(std::string_view bytes) {
  return pkm::parse_machine_text(std::string(bytes), "fuzz.yaml").ok();
}

/// `--load @FILE.yaml` (parse_load_yaml on the file's text), `--load @FILE.csv` (parse_load_csv) and, for the
/// same bytes, the `--load key=value` text form; a leading '@' would make the latter read a file, so that
/// case is left to the file readers.
inline bool run_load(std::string_view bytes) {
  const bool csv = pkm::statics::parse_load_csv(bytes, "fuzz.csv").ok();
  const bool yaml = pkm::statics::parse_load_yaml(std::string(bytes), "fuzz.yaml").ok() || csv;
  if (!bytes.empty() && bytes.front() == '@') return yaml;
  const bool text = pkm::statics::parse_load_spec(bytes).ok();
  return yaml || text;
}

/// steps.csv as read_steps_csv reads it.
inline bool run_steps_csv(std::string_view bytes) {
  return pkm::interpolation::parse_steps_csv(bytes, "fuzz.csv").ok();
}

/// `pkm play steps.bin`: StepStreamReader::open, then every period. The reader only takes a path (it preads a
/// regular file), so the bytes go into an anonymous in-memory file opened through /proc/self/fd. The stored
/// CRC is set to the right one first: otherwise nearly every mutation would stop at the checksum and the
/// period decoder behind it would never be reached (a wrong CRC is covered by step_stream_test).
inline bool run_steps_bin(std::string_view bytes) {
  std::string data(bytes);
  constexpr std::size_t kEndRecord = 24;
  if (data.size() >= kEndRecord && data.compare(data.size() - kEndRecord, 8, "PKMSTEND") == 0) {
    const std::uint32_t crc = pkm::interpolation::step_stream_crc32(data.data(), data.size() - kEndRecord);
    for (int i = 0; i < 4; ++i) data[data.size() - 8 + i] = static_cast<char>((crc >> (8 * i)) & 0xFFU);
  }
  const int descriptor = ::memfd_create("pkm-fuzz-steps", MFD_CLOEXEC);
  if (descriptor < 0) return false;
  bool accepted = false;
  if (::write(descriptor, data.data(), data.size()) == static_cast<ssize_t>(data.size())) {
    pkm::interpolation::StepStreamReader reader;
    if (reader.open("/proc/self/fd/" + std::to_string(descriptor))) {
      pkm::interpolation::StepPeriod period;
      while (reader.next(period)) {
      }
      accepted = !reader.error().has_value();
    }
  }
  ::close(descriptor);
  return accepted;
}

/// The harness of a regression folder name (fuzz/regressions/NAME/), nullptr for an unknown name.
inline bool (*entry_for(std::string_view name))(std::string_view) {
  if (name == "gcode") return run_gcode;
  if (name == "cl") return run_cl;
  if (name == "machine") return run_machine;
  if (name == "load") return run_load;
  if (name == "steps_csv") return run_steps_csv;
  if (name == "steps_bin") return run_steps_bin;
  return nullptr;
}

}  // namespace pkm::fuzz
