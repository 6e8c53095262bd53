#pragma once
// Numbers as APT CL data writes them: `1.5`, `-.5`, `+2.`, `1E-3`, `1.0000E+02`.
#include <optional>
#include <string_view>

namespace pkm::program {

/// The value of `text` (already trimmed) if the whole of it is one finite decimal number; nullopt otherwise
/// (empty, trailing characters, `inf`, `nan`, hexadecimal).
std::optional<double> parse_cl_number(std::string_view text);

}  // namespace pkm::program
