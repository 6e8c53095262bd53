#pragma once
// The one way pkm reads a file the user names (part programs, CL data, tool tables, machine and load files,
// steps files, a run's summary): it never throws, refuses what is not a regular file (a directory, /dev/zero,
// a FIFO) and files above a size cap before reading a byte, and says why with the system's reason.
#include <cstddef>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace pkm {

/// Largest input file pkm reads whole: far above any real part program or machine file (a 3-million-line
/// program is about 80 MiB), small enough that a wrong file cannot exhaust the memory.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{256} << 20;

/// How a reader takes the file: whole into memory (capped at kMaxInputFileBytes) or streamed line by line
/// (a run's CSV files, which grow with the run, have no cap).
enum class InputReading { whole, streamed };

/// Ok when `path` names a regular file (after symlinks), of at most kMaxInputFileBytes if read whole.
/// Errors (ErrorCode::io) read "PATH: cannot read WHAT: REASON", e.g. "prog.ngc: cannot read part program:
/// is a directory". Readers that stream a file call it before opening it.
Status check_input_file(const std::string& path, std::string_view what,
                        InputReading reading = InputReading::whole);

/// The file's bytes, after check_input_file.
Result<std::string> read_input_file(const std::string& path, std::string_view what);

/// A text file as the line readers want it: read_input_file, without a leading UTF-8 byte-order mark (an
/// editor's invisible marker, not part of the first line), and with every lone carriage return (old Mac
/// line ends) turned into a line feed. CR LF stays as it is; byte offsets, so columns, do not change except
/// for the mark's three bytes.
Result<std::string> read_text_input(const std::string& path, std::string_view what);

/// The same normalisation for text already in memory (a test, or text from another source).
std::string normalize_text_input(std::string text);

}  // namespace pkm
