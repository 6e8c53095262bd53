#pragma once
// A single file a command writes at a path the user names (a Bode table, a stiffness or frequency map). In a
// folder that holds an output set (its manifest.json) the file joins that set, as pkm servo's files join a
// plan's: the folder stays one complete set that pkm report reads whole, instead of a set with a stranger
// beside it that every reader refuses. Elsewhere the file is written atomically on its own.
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace pkm {

/// Writes `text` to `path`: joining the output set of its folder when there is one, otherwise atomically.
/// Errors (ErrorCode::io) name the file or the folder.
Status write_output_file(const std::string& path, std::string_view text);

}  // namespace pkm
