#include "io/output_target.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <system_error>

namespace pkm {

namespace {

std::string output_target_reason(int error_number) {
  return std::error_code(error_number, std::generic_category()).message();
}

Error output_target_refused(const std::string& path, const char* kind) {
  return make_error(
      ErrorCode::io,
      fmt::format("cannot write {}: it is {}; pkm writes regular files (replacing them whole) and "
                  "character devices such as /dev/stdout (writing through), nothing else",
                  path, kind));
}

}  // namespace

Result<OutputTargetKind> classify_output_target(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return OutputTargetKind::replace;  // absent or a dangling link
  if (S_ISCHR(status.st_mode) || S_ISFIFO(status.st_mode)) return OutputTargetKind::write_through;
  if (S_ISSOCK(status.st_mode)) return output_target_refused(path, "a socket");
  if (S_ISBLK(status.st_mode)) return output_target_refused(path, "a block device");
  return OutputTargetKind::replace;
}

Result<int> open_write_through(const std::string& path) {
  // O_NONBLOCK: a FIFO nobody reads fails with ENXIO at once instead of blocking the run.
  const int descriptor = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (descriptor < 0 && errno == ENXIO)
    return make_error(ErrorCode::io,
                      fmt::format("cannot write {}: it is a FIFO with no reader; pkm writes regular "
                                  "files (replacing them whole), and character devices and FIFOs "
                                  "being read (writing through)",
                                  path));
  if (descriptor < 0)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: {}", path, output_target_reason(errno)));
  const int flags = ::fcntl(descriptor, F_GETFL);
  if (flags >= 0) ::fcntl(descriptor, F_SETFL, flags & ~O_NONBLOCK);  // then write as to any file
  return descriptor;
}

Status copy_file_into(const std::string& source, int target_descriptor, const std::string& target_name) {
  const int in = ::open(source.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0)
    return make_error(ErrorCode::io,
                      fmt::format("cannot write {}: {}", target_name, output_target_reason(errno)));
  std::array<char, 1 << 16> buffer{};
  for (;;) {
    const ssize_t got = ::read(in, buffer.data(), buffer.size());
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      const int error_number = got < 0 ? errno : 0;
      ::close(in);
      if (error_number == 0) return ok_status();
      return make_error(ErrorCode::io,
                        fmt::format("cannot write {}: {}", target_name, output_target_reason(error_number)));
    }
    for (ssize_t done = 0; done < got;) {
      const ssize_t put =
          ::write(target_descriptor, buffer.data() + done, static_cast<std::size_t>(got - done));
      if (put < 0 && errno == EINTR) continue;
      if (put <= 0) {
        const int error_number = put < 0 ? errno : EIO;
        ::close(in);
        return make_error(ErrorCode::io, fmt::format("cannot write {}: {}", target_name,
                                                     output_target_reason(error_number)));
      }
      done += put;
    }
  }
}

Status sync_path(const std::string& path) {
  const int descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: {}", path, output_target_reason(errno)));
  const int synced = ::fsync(descriptor);
  const int error_number = errno;
  ::close(descriptor);
  if (synced != 0 && error_number != EINVAL && error_number != EROFS)  // some file systems cannot sync dirs
    return make_error(ErrorCode::io,
                      fmt::format("cannot write {}: {}", path, output_target_reason(error_number)));
  return ok_status();
}

}  // namespace pkm
