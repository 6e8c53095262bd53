#pragma once
// The options every command that reads a part program takes, as LinuxCNC's INI and tool table give them to
// its interpreter: --tool-table, --subroutine-path (repeatable, or a colon-separated list as in
// [RS274NGC] SUBROUTINE_PATH), --parameter-file and --write-parameter-file; and --format / --no-transform,
// which say how to read CL data.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "pipeline/load_program.hpp"

namespace pkm::cli {

struct ProgramArguments {
  pipeline::ProgramOptions given;            ///< as parsed; subroutine_path not yet split
  std::vector<std::string> subroutine_path;  ///< each --subroutine-path as given
  /// The options for the interpreter: the subroutine folders split at ':' in the order given.
  pipeline::ProgramOptions options() const;
};

/// Adds the options to `cmd`; `with_tool_table` false for commands that add --tool-table themselves.
void add_program_options(CLI::App& cmd, ProgramArguments& arguments, bool with_tool_table = true);

}  // namespace pkm::cli
