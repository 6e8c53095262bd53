#pragma once
// Writing files so that nobody ever sees a half-written one: the text goes to a temporary file in the same
// directory (a rename is atomic only within one file system) and is renamed over the path when complete.
// A failure at any step removes the temporary and reports the path with the system's reason.
//
// Atomic for readers, not durable: nothing is fsync'ed, so a power loss right after the rename may lose the
// new content. Everything pkm writes can be produced again, and syncing large plan outputs costs seconds.
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace pkm {

/// A file written under a temporary name next to its path (`path.tmp-XXXXXX`) and renamed into place by
/// commit(). Destroyed without a successful commit() it removes the temporary, so a run that fails half way
/// leaves neither a partial file nor a stray temporary. The file gets the permissions of a newly created one
/// (0666 less the umask), also when it replaces an existing file. A path that is a character device is
/// written through instead (never replaced); a FIFO, socket or block device is refused
/// (io/output_target.hpp).
class StagedFile {
 public:
  StagedFile() = default;
  ~StagedFile();
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  /// Creates the temporary for `path`. Call once.
  Status open(const std::string& path);
  /// Appends `text` to the temporary. After a failure the temporary is gone and later calls fail.
  Status write(std::string_view text);
  /// Flushes what was written to the disk (fsync), for files that must survive a power cut.
  Status sync();
  /// Closes the temporary and renames it to the path.
  Status commit();

  const std::string& path() const { return path_; }

 private:
  Error failure(int error_number);  // removes the temporary; the Error names path_ and the reason
  void discard();

  std::string path_;
  std::string temporary_;
  int descriptor_ = -1;
  bool committed_ = false;
};

/// Six random letters and digits for a temporary name next to a file (`.tmp-XXXXXX`, `.old-XXXXXX`).
std::string random_file_suffix();

/// Writes `text` to `path` through a StagedFile. Errors (ErrorCode::io) read "cannot write PATH: REASON".
Status write_file_atomically(const std::string& path, std::string_view text);

}  // namespace pkm
