#include "io/output_set.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <set>
#include <system_error>

#include "io/atomic_file.hpp"
#include "io/output_cleanup.hpp"
#include "io/output_context.hpp"
#include "io/output_target.hpp"

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
Status output_set_make_directories(const fs::path& directory, std::vector<std::string>& created,
                                   std::vector<int>& slots) {
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
    const SignalBlock hold_signals;  // made and registered for cleanup as one step
    if (::mkdir(it->c_str(), 0777) == 0) {
      created.push_back(it->string());
      slots.push_back(register_cleanup(it->string(), CleanupKind::empty_directory));
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

std::string output_set_canonical(const std::string& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  const fs::path canonical = fs::weakly_canonical(absolute, error);
  return (error ? absolute.lexically_normal() : canonical).string();
}

// A temporary for a device target: not beside the device (never create files in /dev), but in the staging
// folder or the system's temporary folder.
Result<std::string> output_set_device_temporary(const std::string& staging, const std::string& target) {
  std::string pattern = staging.empty() ? (fs::temp_directory_path() / "pkm-through-XXXXXX").string()
                                        : (fs::path(staging) / "through-XXXXXX").string();
  const int descriptor = ::mkstemp(pattern.data());
  if (descriptor < 0) return output_set_error(target, errno);
  ::close(descriptor);
  return pattern;
}

}  // namespace

OutputSet::OutputSet(std::string command) : command_(std::move(command)) {}

OutputSet::~OutputSet() {
  if (!committed_) discard();
}

Status OutputSet::open_directory(const std::string& directory) {
  directory_ = directory;
  if (auto made = output_set_make_directories(fs::path(directory), created_directories_, created_slots_);
      !made)
    return made;
  canonical_directory_ = output_set_canonical(directory);
  // A set inside another set's staging folder (pkm strategies plans each strategy into one) is part of that
  // set: the outer one holds the lock and writes the manifest.
  const fs::path canonical(canonical_directory_);
  nested_ = std::any_of(canonical.begin(), canonical.end(),
                        [](const fs::path& part) { return part.string().rfind(".pkm-staging-", 0) == 0; });
  if (nested_) joining_ = false;
  if (Status locked = nested_ ? ok_status() : lock_.acquire(directory); !locked) return locked;
  std::string pattern = (fs::path(directory) / ".pkm-staging-XXXXXX").string();
  const SignalBlock hold_signals;  // a signal between making the folder and registering it would leave it
  if (::mkdtemp(pattern.data()) == nullptr) {
    const int error_number = errno;
    return make_error(ErrorCode::io, fmt::format("cannot write into directory {}: {}", directory,
                                                 output_set_reason(error_number)));
  }
  staging_ = pattern;
  staging_slot_ = register_cleanup(staging_, CleanupKind::tree);
  return ok_status();
}

Status OutputSet::use_directory(const std::string& directory) {
  return open_directory(directory);
}

Status OutputSet::join_directory(const std::string& directory, const std::vector<std::string>& commands) {
  struct stat status {};
  if (::stat(directory.c_str(), &status) != 0 || !S_ISDIR(status.st_mode))
    return make_error(ErrorCode::io, fmt::format("{}: not a directory", directory));
  joining_ = true;
  if (Status opened = open_directory(directory); !opened) return opened;
  // Under the lock: nobody changes the folder before commit().
  if (Status checked = check_output_set(directory, commands); !checked) return checked;
  auto manifest = read_output_manifest(directory);
  if (!manifest) return manifest.error();
  previous_manifest_ = *manifest;
  return ok_status();
}

std::string OutputSet::staged_path(std::string_view name) {
  Member member;
  member.temporary = (fs::path(staging_) / name).string();
  member.target = (fs::path(directory_) / name).string();
  member.listed = fs::path(name).generic_string();
  members_.push_back(member);
  if (fs::path(name)
          .has_parent_path()) {  // a subfolder of the set (a strategy's run): made in the staging folder
    std::error_code ignored;     // a failure shows when the file is written
    fs::create_directories(fs::path(member.temporary).parent_path(), ignored);
  }
  return member.temporary;
}

// The file's name in DIR's manifest when `path` is inside DIR (a report page beside the run's files), "" when
// outside; an Error when it would overwrite a file of this very set, or the manifest.
Result<std::string> OutputSet::listed_name(const std::string& path) const {
  if (canonical_directory_.empty()) return std::string();
  const fs::path target(output_set_canonical(path));
  const fs::path relative = target.lexically_relative(canonical_directory_);
  if (relative.empty() || *relative.begin() == ".." || relative == ".") return std::string();
  const std::string name = relative.generic_string();
  // A joining command (pkm servo --report beside a plan) may replace the set's page, not its data.
  const bool joined_data =
      joining_ && previous_manifest_ && fs::path(name).extension() != ".html" &&
      std::binary_search(previous_manifest_->files.begin(), previous_manifest_->files.end(), name);
  const bool own =
      name == kManifestName || joined_data ||
      std::any_of(members_.begin(), members_.end(), [&](const Member& m) { return m.listed == name; });
  if (own)
    return make_error(ErrorCode::io,
                      fmt::format("cannot write {}: it is a file of this run's own output set in {}; "
                                  "give it another name",
                                  path, directory_));
  return name;
}

Result<std::string> OutputSet::stage_file(const std::string& path) {
  auto target = classify_output_target(path);
  if (!target) return target.error();
  auto listed = listed_name(path);
  if (!listed) return listed.error();
  if (*target == OutputTargetKind::write_through) {
    const SignalBlock hold_signals;  // made and registered for cleanup as one step
    auto temporary = output_set_device_temporary(staging_, path);
    if (!temporary) return temporary;
    Member member{*temporary, path, {}, {}, false, true, -1};
    if (staging_.empty()) member.cleanup_slot = register_cleanup(*temporary, CleanupKind::file);
    members_.push_back(member);
    return *temporary;
  }
  const fs::path file(path);
  if (file.has_parent_path()) {
    if (auto made = output_set_make_directories(file.parent_path(), created_directories_, created_slots_);
        !made)
      return made.error();
  }
  for (int attempt = 0; attempt < kOutputSetNameAttempts; ++attempt) {
    std::string candidate = path + ".tmp-" + random_file_suffix();
    const SignalBlock hold_signals;  // made and registered for cleanup as one step
    const int descriptor = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor >= 0) {
      ::close(descriptor);
      Member member{candidate, path, *listed, {}, false, false, -1};
      member.cleanup_slot = register_cleanup(candidate, CleanupKind::file);
      members_.push_back(member);
      return candidate;
    }
    if (errno != EEXIST) return output_set_error(path, errno);
  }
  return output_set_error(path, EEXIST);
}

Status OutputSet::commit() {
  // Everything that can be checked is checked before the first change, so that the common failures (a
  // directory where a file should go, a folder of another command) leave the previous run untouched.
  if (Status checked = check_targets(); !checked) return checked;
  std::vector<std::string> stale;
  std::optional<OutputManifest> next;
  if (!directory_.empty() && !nested_) {
    auto manifest = next_manifest(stale);
    if (!manifest) return manifest.error();
    next = std::move(*manifest);
  }
  if (Status synced = sync_new_files(); !synced) return synced;
  const SignalBlock hold_signals;
  if (Status written = write_through_devices(); !written) return written;
  if (next) {
    OutputManifest during = *next;  // lists the old set's files too, until they are gone
    during.complete = false;
    if (previous_manifest_)
      during.files.insert(during.files.end(), previous_manifest_->files.begin(),
                          previous_manifest_->files.end());
    manifest_touched_ = true;
    if (Status marked = write_output_manifest(directory_, during); !marked) {
      restore_manifest();
      return marked;
    }
  }
  if (Status placed = place_members(); !placed) return placed;
  // From here the new files are in place and there is no going back: a failure to sync or to write the
  // complete manifest is reported, and leaves the incomplete manifest that readers refuse.
  remove_stale(stale);
  Status finished = sync_folders();
  if (finished && next) finished = write_output_manifest(directory_, *next);
  for (Member& m : members_) {
    if (!m.backup.empty()) ::unlink(m.backup.c_str());
    if (m.write_through) ::unlink(m.temporary.c_str());
    m.backup.clear();
  }
  if (!staging_.empty()) {
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
  }
  lock_.release();
  forget_cleanup();
  committed_ = true;
  return finished;
}

Status OutputSet::check_targets() const {
  std::set<std::string> targets;
  for (const Member& m : members_) {
    bool is_directory = false;
    if (!output_set_exists(m.temporary, is_directory))
      return make_error(ErrorCode::io, fmt::format("cannot write {}: it was not written", m.target));
    if (!m.write_through && output_set_exists(m.target, is_directory) && is_directory)
      return output_set_error(m.target, EISDIR);
    if (!targets.insert(output_set_canonical(m.target)).second)
      return make_error(
          ErrorCode::io,
          fmt::format("cannot write {}: it is a file of this run's own output set; give it another "
                      "name",
                      m.target));
  }
  return ok_status();
}

// The manifest the folder gets, and the files of the old set to remove; refuses a folder this run may not
// replace.
Result<OutputManifest> OutputSet::next_manifest(std::vector<std::string>& stale) {
  auto previous = read_output_manifest(directory_);
  if (!previous) return previous.error();
  previous_manifest_ = *previous;
  std::vector<std::string> names;
  for (const Member& m : members_)
    if (!m.listed.empty()) names.push_back(m.listed);
  const OutputContext context = output_context();
  const std::string command = command_.empty() ? context.command : command_;
  if (joining_) {
    OutputManifest joined = **previous;  // join_directory() checked that there is one, complete
    OutputManifest added = new_output_manifest(command, names);
    joined.files.insert(joined.files.end(), added.files.begin(), added.files.end());
    std::sort(joined.files.begin(), joined.files.end());
    joined.files.erase(std::unique(joined.files.begin(), joined.files.end()), joined.files.end());
    // One entry per joining command: a second pkm report replaces the first's (its files stay listed).
    nlohmann::json kept = nlohmann::json::array();
    for (const auto& entry : joined.joined)
      if (entry.value("command", "") != added.command) kept.push_back(entry);
    joined.joined = std::move(kept);
    joined.joined.push_back({{"command", added.command},
                             {"pkm_version", added.pkm_version},
                             {"inputs", added.inputs},
                             {"files", added.files}});
    return joined;
  }
  const OutputManifest next = new_output_manifest(command, names);
  const OutputFolderContents contents = scan_output_folder(directory_);
  const std::string manifest_path = (fs::path(directory_) / kManifestName).string();
  // Files no manifest lists (an older pkm's run, the user's own): never deleted; with --force left where they
  // are beside the new set.
  std::vector<std::string> unlisted = contents.others;
  for (const std::string& file : contents.files)
    if (!*previous || !std::binary_search((*previous)->files.begin(), (*previous)->files.end(), file))
      unlisted.push_back(file);
  std::erase_if(unlisted, [&](const std::string& file) {
    return std::find(others_allowed_.begin(), others_allowed_.end(), file) != others_allowed_.end();
  });
  if (!unlisted.empty() && !context.force)
    return make_error(ErrorCode::io,
                      fmt::format("cannot write into directory {}: {} is in no pkm output set ({}); pkm "
                                  "replaces only its own sets: give an empty or new folder, or --force to "
                                  "write beside it",
                                  directory_, (fs::path(directory_) / unlisted.front()).string(),
                                  *previous ? "not in " + manifest_path : "no " + manifest_path));
  if (!*previous) return next;
  const OutputManifest& old = **previous;
  if (old.command != command && !context.force)
    return make_error(ErrorCode::io,
                      fmt::format("cannot write into directory {}: it holds the output of pkm {} "
                                  "({}); give another folder, or --force to replace that set whole",
                                  directory_, old.command, manifest_path));
  for (const std::string& file : old.files)
    if (!std::binary_search(next.files.begin(), next.files.end(), file)) stale.push_back(file);
  return next;
}

Status OutputSet::sync_new_files() const {
  for (const Member& m : members_)
    if (Status synced = sync_path(m.temporary); !synced) return synced;
  if (!staging_.empty()) return sync_path(staging_);
  return ok_status();
}

Status OutputSet::write_through_devices() {
  for (const Member& m : members_) {
    if (!m.write_through) continue;
    auto descriptor = open_write_through(m.target);
    if (!descriptor) return descriptor.error();
    Status copied = copy_file_into(m.temporary, *descriptor, m.target);
    if (::close(*descriptor) != 0 && copied) copied = output_set_error(m.target, errno);
    if (!copied) return copied;
  }
  return ok_status();
}

Status OutputSet::place_members() {
  for (Member& m : members_) {
    if (m.write_through) continue;
    if (!m.listed.empty() && fs::path(m.listed).has_parent_path()) {  // its subfolder of DIR, if missing
      Status made =
          output_set_make_directories(fs::path(m.target).parent_path(), created_directories_, created_slots_);
      if (!made) {
        roll_back();
        return made;
      }
    }
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
  return ok_status();
}

// The old set's files the new one does not have, and their folders once empty (a strategy's subfolder).
void OutputSet::remove_stale(const std::vector<std::string>& stale) {
  for (const std::string& name : stale) {
    const fs::path file = fs::path(directory_) / name;
    ::unlink(file.c_str());
    for (fs::path folder = fs::path(name).parent_path(); !folder.empty(); folder = folder.parent_path())
      ::rmdir((fs::path(directory_) / folder).c_str());  // only while empty
  }
}

Status OutputSet::sync_folders() const {
  std::set<std::string> folders;
  for (const Member& m : members_)
    if (!m.write_through) folders.insert(fs::path(m.target).parent_path().string());
  for (const std::string& folder : folders)
    if (Status synced = sync_path(folder.empty() ? "." : folder); !synced) return synced;
  return ok_status();
}

void OutputSet::roll_back() {
  for (auto it = members_.rbegin(); it != members_.rend(); ++it) {
    if (it->placed) ::unlink(it->target.c_str());
    it->placed = false;
    if (!it->backup.empty()) std::rename(it->backup.c_str(), it->target.c_str());
    it->backup.clear();
  }
  restore_manifest();
}

void OutputSet::restore_manifest() {
  if (!manifest_touched_) return;
  manifest_touched_ = false;
  if (previous_manifest_) {
    (void)write_output_manifest(directory_, *previous_manifest_);
  } else {
    ::unlink((fs::path(directory_) / kManifestName).c_str());
  }
}

void OutputSet::discard() {
  roll_back();
  for (const Member& m : members_) ::unlink(m.temporary.c_str());
  if (!staging_.empty()) {
    std::error_code ignored;
    fs::remove_all(staging_, ignored);  // also what a writer left there after its own failure
  }
  lock_.release();
  for (auto it = created_directories_.rbegin(); it != created_directories_.rend(); ++it)
    ::rmdir(it->c_str());  // only while empty: never a file that was there before
  forget_cleanup();
}

void OutputSet::forget_cleanup() {
  unregister_cleanup(staging_slot_);
  staging_slot_ = -1;
  for (Member& m : members_) {
    unregister_cleanup(m.cleanup_slot);
    m.cleanup_slot = -1;
  }
  for (const int slot : created_slots_) unregister_cleanup(slot);
  created_slots_.clear();
}

}  // namespace pkm
