#include "program_options.hpp"

#include <fmt/format.h>

namespace pkm::cli {

pipeline::ProgramOptions ProgramArguments::options() const {
  pipeline::ProgramOptions options = given;
  options.subroutine_path = pipeline::split_search_path(subroutine_path);
  return options;
}

void add_program_options(CLI::App& cmd, ProgramArguments& arguments, bool with_tool_table) {
  if (with_tool_table)
    cmd.add_option("--tool-table", arguments.given.tool_table_path,
                   "LinuxCNC tool table for G43 (lengths in mm)");
  // Repeating the option appends (CLI11's default for a vector); a ':' list is split later, so that
  // "--subroutine-path a:b --subroutine-path c" searches a, b, c.
  cmd.add_option("--subroutine-path", arguments.subroutine_path,
                 "folder searched for subroutine files (o<name> call); repeatable, or a colon-separated list "
                 "like LinuxCNC's [RS274NGC] SUBROUTINE_PATH")
      ->allow_extra_args(false);
  auto* parameter_file = cmd.add_option("--parameter-file", arguments.given.parameter_file,
                                        "LinuxCNC parameter file (.var) read at the start: work offsets, "
                                        "G28/G30 positions, persistent parameters");
  cmd.add_option("--max-blocks", arguments.given.max_blocks,
                 "executed blocks (loop bodies count each time) after which a program is refused as one that "
                 "never ends; default 100000000")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 62));
  cmd.add_option_function<std::string>(
         "--format",
         [&arguments](const std::string& key) {
           // CLI11 has checked the key (check below); parse cannot fail here.
           arguments.given.format =
               program::parse_program_format(key).value_or(program::ProgramFormat::automatic);
         },
         fmt::format("the program's language and CAM dialect: {} (default auto: from the file's content, "
                     "whatever its extension)",
                     program::program_format_keys()))
      ->check([](const std::string& key) {
        return program::parse_program_format(key)
                   ? std::string()
                   : fmt::format("unknown format '{}': one of {}", key, program::program_format_keys());
      });
  cmd.add_flag_function(
      "--no-transform", [&arguments](std::int64_t) { arguments.given.apply_cl_transforms = false; },
      "CL data: keep the points and tool axes in the frame the file writes them in (MSYS, CSYS and ROTABL "
      "not applied)");
  cmd.add_flag("--write-parameter-file", arguments.given.write_parameter_file,
               "write the parameters back to --parameter-file at the program's end, as LinuxCNC does")
      ->needs(parameter_file);
}

}  // namespace pkm::cli
