#pragma once
// What an output path names before pkm writes it, and the durability steps of a commit.
//
// pkm replaces only regular files (by renaming a finished temporary over them). A path that exists and is
// something else is never renamed away or unlinked: a character device (/dev/stdout, /dev/null, a terminal)
// or a FIFO with a reader (/dev/stdout as a pipe) is written through, as the user asked; a FIFO without a
// reader (opening it would wait forever), a socket, a block device or a directory is refused with its kind
// named. A symbolic link counts as what it points to.
#include <string>

#include "core/result.hpp"

namespace pkm {

enum class OutputTargetKind {
  replace,        // absent, or a regular file (or a link to one): written by renaming a temporary over it
  write_through,  // a character device or a FIFO: opened and written in place
};

/// The kind of `path`, or an Error (ErrorCode::io) "cannot write PATH: it is a FIFO; ..." for targets pkm
/// must not touch. A directory is left to the caller (whose message names it).
Result<OutputTargetKind> classify_output_target(const std::string& path);

/// Opens a write-through target for writing (a FIFO without blocking for a reader: none is an Error).
Result<int> open_write_through(const std::string& path);

/// Writes the whole of the file `source` into the open descriptor `target_descriptor` (a device).
Status copy_file_into(const std::string& source, int target_descriptor, const std::string& target_name);

/// fsync of a file or directory by path, so that its data (or its entries) survive a power cut.
Status sync_path(const std::string& path);

}  // namespace pkm
