#include "cli_common.hpp"

#include <fmt/format.h>

#include <iostream>

#include "io/json_text.hpp"
#include "io/printable_text.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

int exit_code_for(ErrorCode code) {
  switch (code) {
    case ErrorCode::bad_input:
    case ErrorCode::io:
    case ErrorCode::unsupported:
      return 2;
    case ErrorCode::unreachable:
    case ErrorCode::limit_exceeded:
    case ErrorCode::wrong_branch:
      return 3;
    case ErrorCode::singular:
    case ErrorCode::not_converged:
      return 4;
  }
  return 1;
}

int report_error(const std::string& command, const Error& error) {
  // The one place every message passes: quoted binary input (a CL file that is not text) is escaped here.
  // A progress line still on the terminal ends first, so that the message starts a line of its own.
  finish_active_progress();
  std::cerr << "pkm " << command << ": error: " << printable_text(error.message) << "\n";
  return exit_code_for(error.code);
}

int report_error(const std::string& command, const Error& error, bool json) {
  if (json) {
    nlohmann::json out = {{"code", to_string(error.code)},   {"message", error.message},
                          {"file", error.location.file},     {"line", error.location.line},
                          {"column", error.location.column}, {"key", error.location.key}};
    out["details"] = error.details_json.empty() ? nlohmann::json(nullptr)
                                                : nlohmann::json::parse(error.details_json, nullptr, false);
    print_json({{"error", out}});
  }
  return report_error(command, error);
}

Result<Machine> load_machine_or_report(const std::string& path) {
  return load_machine_file(path);
}

std::string fixed(double value, int decimals) {
  return fmt::format("{:.{}f}", value, decimals);
}

void print_json(const nlohmann::json& json) {
  std::cout << json_text(json) << "\n";
}

}  // namespace pkm::cli
