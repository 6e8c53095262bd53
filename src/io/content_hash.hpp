#pragma once
// The content hash of an input file for an output set's manifest: 64-bit FNV-1a of the file's bytes, as 16
// hex digits. Not a cryptographic hash: it tells which machine file and program a folder was made from, and
// that they changed since, not that nobody forged them.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace pkm {

/// FNV-1a 64 of `bytes`, continuing from `hash` (the offset basis for a fresh hash).
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash = 0xcbf29ce484222325ULL);

/// The FNV-1a 64 of the file at `path` as 16 lower-case hex digits; errors name the path.
Result<std::string> file_content_hash(const std::string& path);

}  // namespace pkm
