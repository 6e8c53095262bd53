#pragma once
// The files of one run as a set: either all of them replace the previous run's, or none does. A command that
// writes several files (pkm plan: actuators.csv, path.csv, summary.json and maybe report.html) must not leave
// a new path.csv beside an old summary.json when it fails half way, since together they would describe a run
// that never happened.
//
// The files of the output directory DIR are written into a staging folder inside DIR
// (`DIR/.pkm-staging-XXXXXX`, so on the same file system), where they can also be read back (the report
// does). Files elsewhere (a --report page, an optimised program) get a reserved temporary next to their path.
// commit() then checks every target, moves the previous files aside (`NAME.old-XXXXXX`), renames the new
// ones into place and only then deletes the previous ones; if any step fails it puts everything back. Until
// commit() succeeds nothing in DIR changes, and the destructor removes the staging folder, the temporaries
// and DIR itself if this set created it and it is still empty.
//
// Like StagedFile this is atomic for failures pkm sees, not for a power cut in the middle of commit().
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace pkm {

class OutputSet {
 public:
  OutputSet() = default;
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Makes DIR (and missing parents) and the staging folder inside it. At most once per set.
  Status use_directory(const std::string& directory);
  /// The staging folder: a directory that reads like DIR will after commit().
  const std::string& staging_directory() const { return staging_; }
  /// Where to write the file `name` of DIR; it joins the set. Requires use_directory().
  std::string staged_path(std::string_view name);
  /// A reserved temporary next to `path` (created empty, parents made as needed) to write the file to; it
  /// joins the set. For files outside DIR.
  Result<std::string> stage_file(const std::string& path);

  /// Puts every file of the set into place, or (on error) none, leaving the previous ones as they were.
  /// Errors name the file: "cannot write DIR/path.csv: Is a directory".
  Status commit();

 private:
  struct Member {
    std::string temporary;
    std::string target;
    std::string backup;  // the previous file while commit() runs
    bool placed = false;
  };
  void roll_back();
  void discard();

  std::string directory_;
  std::string staging_;
  std::vector<std::string> created_directories_;  // by this set, innermost last
  std::vector<Member> members_;
  bool committed_ = false;
};

}  // namespace pkm
