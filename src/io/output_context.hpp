#pragma once
// What every output set of this process records and may do: the command that writes it (the CLI names it
// once, before the command runs), whether it may replace another command's set (--force), and the input
// files whose content hashes go into the manifest. A process-wide setting, because one pkm process runs one
// command, and so that the pipelines need not thread it through every job; library users who never set it
// write sets of the command "library".
#include <string>
#include <utility>
#include <vector>

namespace pkm {

struct OutputContext {
  std::string command = "library";                          // "plan", "calibrate identify", ...
  bool force = false;                                       // replace a set of another command
  std::vector<std::pair<std::string, std::string>> inputs;  // role ("machine", "program") -> path
};

/// Sets the context for every output set made afterwards in this process.
void set_output_context(OutputContext context);
/// A copy of the current context.
OutputContext output_context();

}  // namespace pkm
