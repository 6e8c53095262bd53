#include "pipeline/load_program.hpp"

#include "planning/motion_plan.hpp"
#include "program/part_program.hpp"

namespace pkm::pipeline {

Result<program::CanonicalProgram> load_program_for(const Machine& machine, const std::string& program_path,
                                                   const std::string& tool_table_path) {
  const planning::ProgramStart start = planning::program_start(machine);
  program::InterpretOptions interpret;
  interpret.start_mm = start.start_mm;
  interpret.start_abc_deg = start.start_abc_deg;
  interpret.tool_table_path = tool_table_path;
  return program::load_part_program(program_path, interpret);
}

}  // namespace pkm::pipeline
