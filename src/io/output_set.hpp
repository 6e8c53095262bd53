#pragma once
// The files of one run as a set: either all of them replace the previous run's, or none does. A command that
// writes several files (pkm plan: actuators.csv, path.csv, summary.json and maybe report.html) must not leave
// a new path.csv beside an old summary.json when it fails half way, since together they would describe a run
// that never happened.
//
// The files of the output directory DIR are written into a staging folder inside DIR
// (`DIR/.pkm-staging-XXXXXX`, so on the same file system), where they can also be read back (the report
// does). Files elsewhere (a --report page, an optimised program) get a reserved temporary next to their path.
// The folder holds one set, named by DIR/manifest.json (io/output_manifest.hpp): the command, the pkm
// version, the inputs' content hashes and the files. While the set is open DIR is locked
// (io/folder_lock.hpp): a second run into it is refused at once.
//
// commit(), with SIGINT and SIGTERM held back:
//   1. checks every target, and that DIR holds nothing but a set this command may replace (its own, or
//      another command's with --force; never files of no set);
//   2. fsyncs every new file, marks the manifest incomplete (listing the old and the new files), then moves
//      the previous files aside (`NAME.old-XXXXXX`), renames the new ones into place and removes the files of
//      the old set that the new one does not have;
//   3. fsyncs the folders and writes the complete manifest last (itself fsync'ed and renamed, the folder
//      fsync'ed): that rename is the one step that makes the new set the folder's.
// A failure in 1–2 puts everything back. A power cut inside 2 leaves an incomplete manifest, which readers
// refuse and the next run replaces. Until commit() succeeds nothing in DIR changes, and the destructor (or,
// on a signal, io/output_cleanup.hpp) removes the staging folder, the temporaries, the lock and DIR itself
// if this set created it and it is still empty.
//
// Targets that exist and are not regular files are never replaced: a character device is written through, a
// FIFO, socket or block device refused (io/output_target.hpp). A file outside DIR that is one of the set's
// own
// (`--out run --report run/path.csv`) is refused.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "io/folder_lock.hpp"
#include "io/output_manifest.hpp"

namespace pkm {

class OutputSet {
 public:
  /// A set of `command` ("plan", "calibrate identify"): the kind its manifest names, which decides who may
  /// replace and read the folder. Empty: the command of this process's output context (the CLI's).
  explicit OutputSet(std::string command = {});
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Makes DIR (and missing parents), locks it and makes the staging folder inside it. At most once per set.
  Status use_directory(const std::string& directory);
  /// Adds this run's files to the complete set of one of `commands` that DIR already holds (pkm servo and
  /// pkm report beside a plan): the manifest keeps its command and lists the added files under "joined".
  Status join_directory(const std::string& directory, const std::vector<std::string>& commands);
  /// The staging folder: a directory that reads like DIR will after commit().
  const std::string& staging_directory() const { return staging_; }
  /// Where to write the file `name` of DIR; it joins the set. Requires use_directory().
  std::string staged_path(std::string_view name);
  /// A reserved temporary to write the file at `path` to (created empty, parents made as needed); it joins
  /// the set. For files outside DIR, or beside the staged ones (a report page in DIR).
  Result<std::string> stage_file(const std::string& path);

  /// Files another program writes into DIR as it uses the set (LinuxCNC's parameter file beside its
  /// configuration): a folder holding them is not refused as someone else's, and they are never deleted.
  void allow_files_of_others(std::vector<std::string> names) { others_allowed_ = std::move(names); }

  /// Puts every file of the set into place, or (on error) none, leaving the previous ones as they were.
  /// Errors name the file: "cannot write DIR/path.csv: Is a directory".
  Status commit();

 private:
  struct Member {
    std::string temporary;
    std::string target;
    std::string listed;  // its name in DIR's manifest; empty for files outside DIR
    std::string backup;  // the previous file while commit() runs
    bool placed = false;
    bool write_through = false;  // a device: written in place at commit
    int cleanup_slot = -1;
  };
  Status open_directory(const std::string& directory);
  Result<std::string> listed_name(const std::string& path) const;
  Result<OutputManifest> next_manifest(std::vector<std::string>& stale);
  Status check_targets() const;
  Status write_through_devices();
  Status place_members();
  void remove_stale(const std::vector<std::string>& stale);
  Status sync_new_files() const;
  Status sync_folders() const;
  void roll_back();
  void restore_manifest();
  void discard();
  void forget_cleanup();

  std::string command_;
  std::string directory_;
  std::string canonical_directory_;
  std::string staging_;
  int staging_slot_ = -1;
  bool joining_ = false;
  bool nested_ = false;  // inside another set's staging folder: no lock, no manifest of its own
  std::optional<OutputManifest> previous_manifest_;
  bool manifest_touched_ = false;
  FolderLock lock_;
  std::vector<std::string> created_directories_;  // by this set, innermost last
  std::vector<int> created_slots_;
  std::vector<Member> members_;
  std::vector<std::string> others_allowed_;
  bool committed_ = false;
};

}  // namespace pkm
