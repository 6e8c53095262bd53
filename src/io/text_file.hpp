#pragma once
// Reading a whole text file (part programs, tool tables, steps files) through the guarded reader
// (io/input_file.hpp): no directories or devices, a size cap, no byte-order mark, lone CRs as line ends.
#include <string>

#include "core/result.hpp"

namespace pkm {

/// The file's text; `what` names it in the error ("PATH: cannot read part program: REASON").
Result<std::string> read_text_file(const std::string& path, const char* what);

}  // namespace pkm
