#pragma once
// What the CLI tells every output set of the run (io/output_context.hpp): the command's full name, whether
// --force was given, and the machine file and part program whose content hashes go into the manifest.
// Commands that write an output folder get --force here, in one place.
#include <CLI/CLI.hpp>

namespace pkm::cli {

/// A subcommand's name with its parents': "calibrate plan".
std::string full_command_name(const CLI::App& sub);

/// Adds --force to the commands that write an output folder, and sets the output context from the parsed
/// command line before the command runs.
void add_output_options(CLI::App& app);

}  // namespace pkm::cli
