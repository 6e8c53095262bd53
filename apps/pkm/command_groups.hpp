#pragma once
// The shape of `pkm --help` and of a command pkm does not know: the subcommands in five groups (plan and
// run, analyse, machine, calibration, tools) with an example line each, and `pkm foo` answered as an
// unknown command with the list of commands.
#include <CLI/CLI.hpp>
#include <optional>

namespace pkm::cli {

/// Puts every subcommand of `app` into its group and adds the examples to the help's footer.
void group_commands(CLI::App& app);

/// When argv[1] is neither an option nor a command of `app`: prints "pkm: error: unknown command 'foo'"
/// with the commands and returns 2; otherwise std::nullopt.
std::optional<int> refuse_unknown_command(CLI::App& app, int argc, char** argv);

}  // namespace pkm::cli
