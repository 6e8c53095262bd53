#pragma once
// Shared pieces of the pkm subcommands: loading the machine, reporting errors, exit codes.
#include <nlohmann/json.hpp>
#include <string>

#include "io/machine_file.hpp"
#include "io/output_set.hpp"

namespace pkm::cli {

/// Exit codes (docs/cli.md): 0 success, 2 bad input or file, 3 unreachable / out of limits / other assembly
/// mode, 4 singular or not converged. CLI11 usage errors keep CLI11's own non-zero codes.
int exit_code_for(ErrorCode code);

/// Prints "pkm <command>: error: <message>" on stderr, control bytes and broken UTF-8 escaped, and returns
/// the exit code for the error.
int report_error(const std::string& command, const Error& error);
/// The same, and with `json` also the error as JSON on stdout: {"error": {"code", "message", "file", "line",
/// "column", "key", "details"}} (details: Error::details_json, or null).
int report_error(const std::string& command, const Error& error, bool json);

/// Loads a machine file or reports why not.
Result<Machine> load_machine_or_report(const std::string& path);

/// Formats a number for tables: fixed with `decimals` digits.
std::string fixed(double value, int decimals);

/// Prints JSON (2-space indent) on stdout.
void print_json(const nlohmann::json& json);

}  // namespace pkm::cli
