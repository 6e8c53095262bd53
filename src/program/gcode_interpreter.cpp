// interpret_gcode: RS274/NGC text → canonical moves. The front end (ngc_block_reader) resolves parameters,
// expressions and O-word control flow; the executor (ngc_executor) gives each block its meaning, as
// LinuxCNC's rs274 does (docs/part-programs.md).
#include <optional>

#include "program/ngc_executor.hpp"
#include "program/part_program.hpp"
#include "program/tool_table.hpp"

namespace pkm::program {

Result<CanonicalProgram> interpret_gcode(std::string_view text, const std::string& source_name,
                                         const InterpretOptions& options) {
  std::optional<ToolTable> tools;
  if (!options.tool_table_path.empty()) {
    auto table = read_tool_table(options.tool_table_path);
    if (!table) return table.error();
    tools = std::move(table.value());
  }
  CanonicalProgram program;
  ngc::Executor executor(source_name, options, std::move(tools));
  if (auto run = executor.run(text, program); !run) return run.error();
  program.format = std::string(program_format_name(ProgramFormat::gcode));
  return program;
}

}  // namespace pkm::program
