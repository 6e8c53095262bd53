#pragma once
// JSON as text, the one way pkm writes it. Paths and program text can hold bytes that are not UTF-8 (a file
// name on a Latin-1 disk, a comment in a CAM file); nlohmann's default dump throws on them and a run would
// end in std::terminate after all its work. Here such bytes become U+FFFD, and the document is written.
#include <nlohmann/json.hpp>
#include <string>

namespace pkm {

/// `json` as text with `indent` spaces (-1: one line), invalid UTF-8 replaced by U+FFFD.
inline std::string json_text(const nlohmann::json& json, int indent = 2) {
  return json.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace pkm
