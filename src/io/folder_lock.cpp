#include "io/folder_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "io/output_cleanup.hpp"

namespace pkm {

namespace {

// The holder removes the lock file when done; a run that opened the old file just before must retry on the
// new one, or two runs would each hold a lock on a different file.
constexpr int kFolderLockAttempts = 5;

}  // namespace

FolderLock::~FolderLock() {
  release();
}

Status FolderLock::acquire(const std::string& directory) {
  const std::string path = directory + "/" + kFolderLockName;
  for (int attempt = 0; attempt < kFolderLockAttempts; ++attempt) {
    const SignalBlock hold_signals;  // the lock file is made and registered for cleanup as one step
    const int descriptor = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (descriptor < 0)
      return make_error(ErrorCode::io,
                        fmt::format("cannot write into directory {}: cannot create its lock file: {}",
                                    directory, std::error_code(errno, std::generic_category()).message()));
    if (::flock(descriptor, LOCK_EX | LOCK_NB) != 0) {
      ::close(descriptor);
      return make_error(
          ErrorCode::io,
          fmt::format("cannot write into directory {}: another pkm run is writing it now ({} is "
                      "locked); wait for it, or give another folder",
                      directory, path));
    }
    struct stat held {
    }, named{};
    if (::fstat(descriptor, &held) == 0 && ::stat(path.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      path_ = path;
      descriptor_ = descriptor;
      cleanup_slot_ = register_cleanup(path, CleanupKind::file);
      return ok_status();
    }
    ::close(descriptor);  // the file was removed and made again under us: lock the current one
  }
  return make_error(
      ErrorCode::io,
      fmt::format("cannot write into directory {}: its lock file {} keeps changing", directory, path));
}

void FolderLock::release() {
  if (descriptor_ < 0) return;
  ::unlink(path_.c_str());  // while still locked: whoever opens the name next makes a fresh file
  ::close(descriptor_);
  descriptor_ = -1;
  unregister_cleanup(cleanup_slot_);
  cleanup_slot_ = -1;
}

}  // namespace pkm
