#pragma once
// An exclusive lock on an output folder for one run, so that two runs into one folder at once cannot mix
// their files: the first takes it and commits whole; the second is refused at once, naming the folder. The
// lock is flock(2) on DIR/.pkm-lock: the kernel drops it when the process ends in any way (a kill, a crash),
// so a stale lock file never blocks a later run. The file is removed again on release.
#include <string>

#include "core/result.hpp"

namespace pkm {

class FolderLock {
 public:
  FolderLock() = default;
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  /// Locks the existing folder `directory` or returns an Error (ErrorCode::io) naming it.
  Status acquire(const std::string& directory);
  /// Unlocks and removes the lock file (also done by the destructor).
  void release();

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int descriptor_ = -1;
  int cleanup_slot_ = -1;
};

/// The lock file's name inside a folder; readers of a set ignore it.
inline constexpr const char* kFolderLockName = ".pkm-lock";

}  // namespace pkm
