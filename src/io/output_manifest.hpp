#pragma once
// The manifest of an output set: DIR/manifest.json names the command that wrote the folder, the pkm
// version, the content hashes of its inputs (machine file, part program) and every file of the set. It is
// written last when a set is committed and read first by every command that reads a folder: a folder without
// one, with files it does not list, missing files it lists, or of another command than the reader needs, is
// refused by name instead of being read as a run that never happened.
//
// While a commit moves files the manifest says "complete": false and lists the old and the new set's files:
// a power cut then leaves a folder that readers refuse and that the next run replaces.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace pkm {

inline constexpr const char* kManifestName = "manifest.json";

struct OutputManifest {
  std::string command;      // "plan", "calibrate identify", ...
  std::string pkm_version;  // of the pkm that wrote the set
  bool complete = true;
  nlohmann::json inputs = nlohmann::json::object();  // role -> {"path", "fnv1a64"}
  std::vector<std::string> files;                    // relative to the folder, '/'-separated, sorted
  nlohmann::json joined = nlohmann::json::array();   // commands that added files to this set (pkm servo)
};

/// A manifest of `command` and this pkm's version for `files`, with the content hashes of this process's
/// inputs (io/output_context.hpp; an input that cannot be read is recorded without one).
OutputManifest new_output_manifest(const std::string& command, std::vector<std::string> files);

/// DIR/manifest.json, std::nullopt when the folder has none; an unreadable or malformed one is an Error that
/// names the file.
Result<std::optional<OutputManifest>> read_output_manifest(const std::string& directory);

/// Writes DIR/manifest.json durably: a temporary, fsync'ed, renamed over the old one, the folder fsync'ed.
Status write_output_manifest(const std::string& directory, const OutputManifest& manifest);

/// The entries of an output folder as a set sees them: its files (relative paths, recursively) and anything
/// else (devices, links, ...), leaving out the manifest, the lock file and pkm's own temporaries.
struct OutputFolderContents {
  std::vector<std::string> files;
  std::vector<std::string> others;
};
OutputFolderContents scan_output_folder(const std::string& directory);

/// For commands that read a folder: ok when DIR holds one complete set of one of `commands` and nothing
/// else. Errors (ErrorCode::io, exit 2) name the folder and the file: "run/: holds the output of pkm
/// stiffness, not of pkm plan (run/manifest.json)", "run/forces.csv: not in run/manifest.json: ...".
/// A path that is not a directory is left to the reader (ok).
Status check_output_set(const std::string& directory, const std::vector<std::string>& commands);

}  // namespace pkm
