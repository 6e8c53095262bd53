#include "io/output_set.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "io/atomic_file.hpp"

namespace pkm {

namespace {

namespace fs = std::filesystem;

constexpr int kOutputSetNameAttempts = 100;

std::string output_set_reason(int error_number) {
  return std::error_code(error_number, std::generic_category()).message();
}

Error output_set_error(const std::string& path, int error_number) {
  return make_error(ErrorCode::io, fmt::format("cannot write {}: {}", path, output_set_reason(error_number)));
}

// Creates `directory` and its missing parents, remembering which it made (outermost first).
Status output_set_make_directories(const fs::path& directory, std::vector<std::string>& created) {
  std::vector<fs::path> missing;
  for (fs::path p = directory; !p.empty(); p = p.parent_path()) {
    struct stat status {};
    if (::stat(p.c_str(), &status) == 0) {
      if (!S_ISDIR(status.st_mode))
        return make_error(ErrorCode::io, fmt::format("cannot create directory {}: {} is not a directory",
                                                     directory.string(), p.string()));
      break;
    }
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) == 0) {
      created.push_back(it->string());
    } else if (errno != EEXIST) {
      return make_error(ErrorCode::io, fmt::format("cannot create directory {}: {}", directory.string(),
                                                   output_set_reason(errno)));
    }
  }
  return ok_status();
}

bool output_set_exists(const std::string& path, bool& is_directory) {
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) return false;
  is_directory = S_ISDIR(status.st_mode);
  return true;
}

}  // namespace

OutputSet::~OutputSet() {
  if (!committed_) discard();
}

Status OutputSet::use_directory(const std::string& directory) {
  directory_ = directory;
  if (auto made = output_set_make_directories(fs::path(directory), created_directories_); !made) return made;
  std::string pattern = (fs::path(directory) / ".pkm-staging-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    const int error_number = errno;
    return make_error(ErrorCode::io, fmt::format("cannot write into directory {}: {}", directory,
                                                 output_set_reason(error_number)));
  }
  staging_ = pattern;
  return ok_status();
}

std::string OutputSet::staged_path(std::string_view name) {
  Member member;
  member.temporary = (fs::path(staging_) / name).string();
  member.target = (fs::path(directory_) / name).string();
  members_.push_back(member);
  return member.temporary;
}

Result<std::string> OutputSet::stage_file(const std::string& path) {
  const fs::path file(path);
  if (file.has_parent_path()) {
    if (auto made = output_set_make_directories(file.parent_path(), created_directories_); !made)
      return made.error();
  }
  for (int attempt = 0; attempt < kOutputSetNameAttempts; ++attempt) {
    std::string candidate = path + ".tmp-" + random_file_suffix();
    const int descriptor = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor >= 0) {
      ::close(descriptor);
      members_.push_back(Member{candidate, path, {}, false});
      return candidate;
    }
    if (errno != EEXIST) return output_set_error(path, errno);
  }
  return output_set_error(path, EEXIST);
}

Status OutputSet::commit() {
  // Everything that can be checked is checked before the first rename, so that the common failures (a
  // directory where a file should go, a file that was never written) leave the previous run untouched.
  for (const Member& m : members_) {
    bool is_directory = false;
    if (!output_set_exists(m.temporary, is_directory))
      return make_error(ErrorCode::io, fmt::format("cannot write {}: it was not written", m.target));
    if (output_set_exists(m.target, is_directory) && is_directory) return output_set_error(m.target, EISDIR);
  }
  for (Member& m : members_) {
    bool is_directory = false;
    if (output_set_exists(m.target, is_directory)) {
      std::string backup = m.target + ".old-" + random_file_suffix();
      if (std::rename(m.target.c_str(), backup.c_str()) != 0) {
        const int error_number = errno;
        roll_back();
        return output_set_error(m.target, error_number);
      }
      m.backup = std::move(backup);
    }
    if (std::rename(m.temporary.c_str(), m.target.c_str()) != 0) {
      const int error_number = errno;
      roll_back();
      return output_set_error(m.target, error_number);
    }
    m.placed = true;
  }
  for (Member& m : members_) {
    if (!m.backup.empty()) ::unlink(m.backup.c_str());
    m.backup.clear();
  }
  if (!staging_.empty()) {
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
  }
  committed_ = true;
  return ok_status();
}

void OutputSet::roll_back() {
  for (auto it = members_.rbegin(); it != members_.rend(); ++it) {
    if (it->placed) ::unlink(it->target.c_str());
    it->placed = false;
    if (!it->backup.empty()) std::rename(it->backup.c_str(), it->target.c_str());
    it->backup.clear();
  }
}

void OutputSet::discard() {
  roll_back();
  for (const Member& m : members_) ::unlink(m.temporary.c_str());
  if (!staging_.empty()) {
    std::error_code ignored;
    fs::remove_all(staging_, ignored);  // also what a writer left there after its own failure
  }
  for (auto it = created_directories_.rbegin(); it != created_directories_.rend(); ++it)
    ::rmdir(it->c_str());  // only while empty: never a file that was there before
}

}  // namespace pkm
