#pragma once
// Cleanup of an output set's temporaries when pkm is stopped by SIGINT or SIGTERM. The sets register what
// they made (the staging folder, temporaries beside targets, the lock file, folders they created); the
// handler removes them with system calls only (async-signal-safe: no allocation, no locks) and ends the
// process with 128 + the signal's number (130, 143), as a shell reports it. The previous complete set is
// never touched by the handler: commit() blocks both signals while it moves files, so a signal arrives
// before or after the commit, never in its middle.
#include <string>

namespace pkm {

enum class CleanupKind { file, tree, empty_directory };

/// Installs the SIGINT and SIGTERM handlers (the CLI does, once; a library user keeps its own handlers).
void install_output_cleanup_handlers();

/// Registers `path` for removal on a signal; returns its slot (or -1 when the table is full: the path is then
/// only removed by the normal flow). Registration order is removal order for empty directories (innermost
/// must be registered last).
int register_cleanup(const std::string& path, CleanupKind kind);
/// Forgets a slot (the path was removed or became part of the committed set).
void unregister_cleanup(int slot);

/// Holds SIGINT and SIGTERM back while alive (a commit's renames; a temporary made and registered): blocked
/// in this thread, recorded by the handler in any other; a signal that came meanwhile is raised again when
/// the outermost block ends. Blocks nest.
class SignalBlock {
 public:
  SignalBlock();
  ~SignalBlock();
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  unsigned char saved_[128];  // the previous sigset_t (kept opaque to keep <signal.h> out of the header)
};

}  // namespace pkm
