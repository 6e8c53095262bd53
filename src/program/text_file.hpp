#pragma once
// Reading a whole text file (part programs, tool tables) with an io error naming the path.
#include <string>

#include "core/result.hpp"

namespace pkm::program {

/// The file's bytes; `what` names it in the error ("cannot read part program").
Result<std::string> read_text_file(const std::string& path, const char* what);

}  // namespace pkm::program
