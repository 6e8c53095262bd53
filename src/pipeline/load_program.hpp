#pragma once
// A part program file read for a machine: the interpreter starts where the machine's program starts (the home
// tool point in program coordinates and its angles), so a first move without some axes keeps them there.
#include <string>

#include "machine/machine.hpp"
#include "program/canonical_program.hpp"

namespace pkm::pipeline {

/// G-code or CL data by extension; `tool_table_path` (may be empty) serves G43.
Result<program::CanonicalProgram> load_program_for(const Machine& machine, const std::string& program_path,
                                                   const std::string& tool_table_path);

}  // namespace pkm::pipeline
