#include "io/input_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace pkm {

namespace {

std::string input_file_reason(int error_number) {
  return std::error_code(error_number, std::generic_category()).message();
}

Error input_file_error(const std::string& path, std::string_view what, std::string_view reason) {
  return make_error(ErrorCode::io, fmt::format("{}: cannot read {}: {}", path, what, reason));
}

std::string input_file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "is a device, not a regular file";
  if (S_ISFIFO(mode)) return "is a pipe, not a regular file";
  if (S_ISSOCK(mode)) return "is a socket, not a regular file";
  return "not a regular file";
}

std::string input_file_too_large(std::size_t bytes) {
  return fmt::format("the file has {} bytes, more than the {} MiB pkm reads", bytes,
                     kMaxInputFileBytes >> 20);
}

}  // namespace

Status check_input_file(const std::string& path, std::string_view what, InputReading reading) {
  if (path.empty()) return input_file_error(path, what, "no file name given");
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) return input_file_error(path, what, input_file_reason(errno));
  if (!S_ISREG(status.st_mode)) return input_file_error(path, what, input_file_kind(status.st_mode));
  if (reading == InputReading::whole && static_cast<std::size_t>(status.st_size) > kMaxInputFileBytes)
    return input_file_error(path, what, input_file_too_large(static_cast<std::size_t>(status.st_size)));
  return ok_status();
}

Result<std::string> read_input_file(const std::string& path, std::string_view what) {
  if (auto checked = check_input_file(path, what); !checked) return checked.error();
  const int descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0) return input_file_error(path, what, input_file_reason(errno));
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(descriptor, buffer, sizeof buffer);
    if (got < 0) {
      if (errno == EINTR) continue;
      const int error_number = errno;
      ::close(descriptor);
      return input_file_error(path, what, input_file_reason(error_number));
    }
    if (got == 0) break;
    // The file may have grown since stat(): the cap holds for what is read, not only for what was seen.
    if (text.size() + static_cast<std::size_t>(got) > kMaxInputFileBytes) {
      ::close(descriptor);
      return input_file_error(path, what, input_file_too_large(text.size() + static_cast<std::size_t>(got)));
    }
    text.append(buffer, static_cast<std::size_t>(got));
  }
  ::close(descriptor);
  return text;
}

std::string normalize_text_input(std::string text) {
  static constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (std::string_view(text).substr(0, kByteOrderMark.size()) == kByteOrderMark)
    text.erase(0, kByteOrderMark.size());
  for (std::size_t i = text.find('\r'); i != std::string::npos; i = text.find('\r', i + 1)) {
    if (i + 1 == text.size() || text[i + 1] != '\n') text[i] = '\n';
  }
  return text;
}

Result<std::string> read_text_input(const std::string& path, std::string_view what) {
  auto bytes = read_input_file(path, what);
  if (!bytes) return bytes.error();
  return normalize_text_input(std::move(*bytes));
}

}  // namespace pkm
