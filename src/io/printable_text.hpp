#pragma once
// Messages quote what the user gave (a CL statement, a YAML value, a file name). Quoted binary must not reach
// the terminal raw: control bytes can move the cursor or change its state, and stray bytes are invisible.
#include <cstddef>
#include <string>
#include <string_view>

namespace pkm {

/// Messages longer than this are cut ("… (N more bytes)"): a 2 MB line quoted whole helps nobody.
inline constexpr std::size_t kMaxPrintableBytes = 1000;

/// `text` with every control byte (below 0x20 and 0x7F) and every byte that is not part of valid UTF-8
/// written as \xNN; well-formed UTF-8 ("…", "°", "ρ") stays as it is. A backslash stays a backslash. At most
/// about `max_bytes` bytes of it, cut between characters.
std::string printable_text(std::string_view text, std::size_t max_bytes = kMaxPrintableBytes);

/// The offset of the first byte printable_text would escape (a control byte, a byte that is not part of
/// valid UTF-8), or std::string_view::npos if there is none: text that prints as it is.
std::size_t first_unprintable_byte(std::string_view text);

}  // namespace pkm
