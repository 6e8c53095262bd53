#include "pipeline/load_program.hpp"

#include "planning/motion_plan.hpp"

namespace pkm::pipeline {

program::InterpretOptions interpret_options(const ProgramOptions& options) {
  program::InterpretOptions interpret;
  interpret.tool_table_path = options.tool_table_path;
  interpret.subroutine_path = options.subroutine_path;
  interpret.parameter_file = options.parameter_file;
  interpret.write_parameter_file = options.write_parameter_file;
  interpret.max_blocks = options.max_blocks;
  interpret.format = options.format;
  interpret.apply_cl_transforms = options.apply_cl_transforms;
  return interpret;
}

program::InterpretOptions interpret_options_for(const Machine& machine, const ProgramOptions& options,
                                                program::MoveSink sink) {
  const planning::ProgramStart start = planning::program_start(machine);
  program::InterpretOptions interpret = interpret_options(options);
  interpret.start_mm = start.start_mm;
  interpret.start_abc_deg = start.start_abc_deg;
  interpret.move_sink = std::move(sink);
  return interpret;
}

Result<program::CanonicalProgram> load_program_for(const Machine& machine, const std::string& program_path,
                                                   const ProgramOptions& options, program::MoveSink sink) {
  return program::load_part_program(program_path, interpret_options_for(machine, options, std::move(sink)));
}

std::vector<std::string> split_search_path(const std::vector<std::string>& given) {
  std::vector<std::string> folders;
  for (const std::string& entry : given) {
    std::size_t begin = 0;
    while (begin <= entry.size()) {
      std::size_t end = entry.find(':', begin);
      if (end == std::string::npos) end = entry.size();
      if (end > begin) folders.push_back(entry.substr(begin, end - begin));
      begin = end + 1;
    }
  }
  return folders;
}

}  // namespace pkm::pipeline
