#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <random>
#include <system_error>

#include "io/output_target.hpp"

namespace pkm {

namespace {

// Another process (or a second StagedFile for the same path) may hold a temporary with the same suffix;
// O_EXCL detects that and a new suffix is drawn. Failing this often means something else is wrong.
constexpr int kAtomicFileNameAttempts = 100;

std::string atomic_file_reason(int error_number) {
  // std::strerror is not thread-safe; the generic category's message is the same text.
  return std::error_code(error_number, std::generic_category()).message();
}

}  // namespace

std::string random_file_suffix() {
  static constexpr char kAlphabet[] = "0123456789abcdefghijklmnopqrstuvwxyz";
  thread_local std::mt19937_64 generator{std::random_device{}()};
  std::uniform_int_distribution<int> pick(0, static_cast<int>(sizeof(kAlphabet)) - 2);
  std::string suffix(6, '0');
  for (char& c : suffix) c = kAlphabet[pick(generator)];
  return suffix;
}

StagedFile::~StagedFile() {
  if (!committed_) discard();
}

void StagedFile::discard() {
  if (descriptor_ >= 0) ::close(descriptor_);
  descriptor_ = -1;
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  temporary_.clear();
}

Error StagedFile::failure(int error_number) {
  discard();
  return make_error(ErrorCode::io,
                    fmt::format("cannot write {}: {}", path_, atomic_file_reason(error_number)));
}

Status StagedFile::open(const std::string& path) {
  path_ = path;
  auto target = classify_output_target(path);
  if (!target) return target.error();
  if (*target == OutputTargetKind::write_through) {
    // A device the user named (/dev/stdout, /dev/null): written in place, never replaced.
    auto descriptor = open_write_through(path);
    if (!descriptor) return descriptor.error();
    descriptor_ = *descriptor;
    return ok_status();
  }
  for (int attempt = 0; attempt < kAtomicFileNameAttempts; ++attempt) {
    std::string candidate = path + ".tmp-" + random_file_suffix();
    // 0666 lets the umask decide, as for any file a program creates.
    const int descriptor = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor >= 0) {
      descriptor_ = descriptor;
      temporary_ = std::move(candidate);
      return ok_status();
    }
    if (errno != EEXIST) return failure(errno);
  }
  return failure(EEXIST);
}

Status StagedFile::write(std::string_view text) {
  if (descriptor_ < 0)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: the file is not open", path_));
  while (!text.empty()) {
    const ssize_t written = ::write(descriptor_, text.data(), text.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return failure(errno);
    }
    text.remove_prefix(static_cast<std::size_t>(written));
  }
  return ok_status();
}

Status StagedFile::sync() {
  if (descriptor_ < 0)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: the file is not open", path_));
  if (::fsync(descriptor_) != 0 && errno != EINVAL) return failure(errno);  // EINVAL: a device cannot sync
  return ok_status();
}

Status StagedFile::commit() {
  if (descriptor_ < 0)
    return make_error(ErrorCode::io, fmt::format("cannot write {}: the file is not open", path_));
  // Some file systems (NFS, full disks with delayed allocation) report write errors only at close.
  const int closed = ::close(descriptor_);
  descriptor_ = -1;
  if (closed != 0) return failure(errno);
  if (temporary_.empty()) {  // written through
    committed_ = true;
    return ok_status();
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) return failure(errno);
  temporary_.clear();
  committed_ = true;
  return ok_status();
}

Status write_file_atomically(const std::string& path, std::string_view text) {
  StagedFile file;
  if (auto opened = file.open(path); !opened) return opened;
  if (auto written = file.write(text); !written) return written;
  return file.commit();
}

}  // namespace pkm
