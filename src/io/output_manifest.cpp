#include "io/output_manifest.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/content_hash.hpp"
#include "io/folder_lock.hpp"
#include "io/json_text.hpp"
#include "io/output_context.hpp"
#include "io/output_target.hpp"
#include "io/version.hpp"

namespace pkm {

namespace {

namespace fs = std::filesystem;

constexpr const char* kManifestFormat = "pkm output set";
constexpr int kManifestFormatVersion = 1;

// pkm's own temporaries (a run in progress, or one killed without cleanup) are not part of any set.
bool output_folder_skips(const std::string& name) {
  return name == kManifestName || name == kFolderLockName || name.rfind(".pkm-staging-", 0) == 0 ||
         name.find(".tmp-") != std::string::npos || name.find(".old-") != std::string::npos;
}

std::string join_path(const std::string& directory, const std::string& name) {
  return (fs::path(directory) / name).string();
}

nlohmann::json manifest_json(const OutputManifest& m) {
  return {{"format", kManifestFormat}, {"format_version", kManifestFormatVersion},
          {"command", m.command},      {"pkm_version", m.pkm_version},
          {"complete", m.complete},    {"inputs", m.inputs},
          {"files", m.files},          {"joined", m.joined}};
}

Result<OutputManifest> manifest_from_json(const nlohmann::json& j, const std::string& path) {
  const auto bad = [&](const char* what) {
    return make_error(ErrorCode::io, fmt::format("{}: not a pkm manifest: {}", path, what));
  };
  if (!j.is_object() || j.value("format", "") != kManifestFormat)
    return bad("no \"format\": \"pkm output set\"");
  OutputManifest m;
  if (!j.contains("command") || !j["command"].is_string()) return bad("no command");
  m.command = j["command"].get<std::string>();
  m.pkm_version = j.value("pkm_version", "");
  m.complete = j.value("complete", false);
  if (j.contains("inputs") && j["inputs"].is_object()) m.inputs = j["inputs"];
  if (j.contains("joined") && j["joined"].is_array()) m.joined = j["joined"];
  if (!j.contains("files") || !j["files"].is_array()) return bad("no list of files");
  for (const auto& file : j["files"]) {
    if (!file.is_string()) return bad("a file name that is not a string");
    const std::string name = file.get<std::string>();
    const fs::path relative(name);
    if (name.empty() || relative.is_absolute() ||
        std::any_of(relative.begin(), relative.end(), [](const fs::path& p) { return p == ".."; }))
      return bad("a file outside the folder");
    m.files.push_back(name);
  }
  std::sort(m.files.begin(), m.files.end());
  return m;
}

}  // namespace

OutputManifest new_output_manifest(const std::string& command, std::vector<std::string> files) {
  const OutputContext context = output_context();
  OutputManifest m;
  m.command = command;
  m.pkm_version = std::string(pkm_version());
  for (const auto& [role, path] : context.inputs) {
    nlohmann::json input = {{"path", path}};
    if (auto hash = file_content_hash(path)) input["fnv1a64"] = *hash;
    m.inputs[role] = input;
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  m.files = std::move(files);
  return m;
}

Result<std::optional<OutputManifest>> read_output_manifest(const std::string& directory) {
  const std::string path = join_path(directory, kManifestName);
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) return std::optional<OutputManifest>{};
  if (!S_ISREG(status.st_mode))
    return make_error(ErrorCode::io, fmt::format("{}: not a pkm manifest: not a regular file", path));
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) return make_error(ErrorCode::io, fmt::format("{}: cannot read the manifest", path));
  const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
  if (j.is_discarded())
    return make_error(ErrorCode::io, fmt::format("{}: not a pkm manifest: not JSON", path));
  auto manifest = manifest_from_json(j, path);
  if (!manifest) return manifest.error();
  return std::optional<OutputManifest>(std::move(*manifest));
}

Status write_output_manifest(const std::string& directory, const OutputManifest& manifest) {
  const std::string path = join_path(directory, kManifestName);
  StagedFile file;
  if (Status opened = file.open(path); !opened) return opened;
  if (Status written = file.write(json_text(manifest_json(manifest)) + "\n"); !written) return written;
  if (Status synced = file.sync(); !synced) return synced;
  if (Status committed = file.commit(); !committed) return committed;
  return sync_path(directory);
}

OutputFolderContents scan_output_folder(const std::string& directory) {
  OutputFolderContents contents;
  std::error_code error;
  fs::recursive_directory_iterator it(directory, error), end;
  for (; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (output_folder_skips(name)) {
      if (it->is_directory(error)) it.disable_recursion_pending();
      continue;
    }
    const std::string relative = fs::relative(it->path(), directory, error).generic_string();
    if (it->is_symlink(error) || !(it->is_regular_file(error) || it->is_directory(error))) {
      contents.others.push_back(relative);
      if (it->is_directory(error)) it.disable_recursion_pending();
    } else if (it->is_regular_file(error)) {
      contents.files.push_back(relative);
    }
  }
  std::sort(contents.files.begin(), contents.files.end());
  std::sort(contents.others.begin(), contents.others.end());
  return contents;
}

Status check_output_set(const std::string& directory, const std::vector<std::string>& commands) {
  struct stat status {};
  if (::stat(directory.c_str(), &status) != 0 || !S_ISDIR(status.st_mode)) return ok_status();
  const std::string manifest_path = join_path(directory, kManifestName);
  auto manifest = read_output_manifest(directory);
  if (!manifest) return manifest.error();
  std::string wanted;
  for (const std::string& command : commands) wanted += (wanted.empty() ? "pkm " : " or pkm ") + command;
  if (!*manifest)
    return make_error(ErrorCode::io,
                      fmt::format("{}: not a complete output set of {}: no {} (written last by "
                                  "the command that makes the folder)",
                                  directory, wanted, manifest_path));
  const OutputManifest& m = **manifest;
  if (!m.complete)
    return make_error(ErrorCode::io,
                      fmt::format("{}: an incomplete output set ({} says a run was stopped while "
                                  "replacing it): run pkm {} again",
                                  directory, manifest_path, m.command));
  if (std::find(commands.begin(), commands.end(), m.command) == commands.end())
    return make_error(ErrorCode::io, fmt::format("{}: holds the output of pkm {}, not of {} ({})", directory,
                                                 m.command, wanted, manifest_path));
  const OutputFolderContents contents = scan_output_folder(directory);
  for (const std::string& file : m.files) {
    if (!std::binary_search(contents.files.begin(), contents.files.end(), file))
      return make_error(ErrorCode::io, fmt::format("{}: listed in {} but missing or not a regular file: a "
                                                   "mixed or damaged output set",
                                                   join_path(directory, file), manifest_path));
  }
  std::vector<std::string> unlisted = contents.others;
  for (const std::string& file : contents.files)
    if (!std::binary_search(m.files.begin(), m.files.end(), file)) unlisted.push_back(file);
  if (!unlisted.empty())
    return make_error(ErrorCode::io,
                      fmt::format("{}: not in {}: a mixed output set (files of another run or "
                                  "command beside pkm {}'s)",
                                  join_path(directory, unlisted.front()), manifest_path, m.command));
  return ok_status();
}

}  // namespace pkm
