#pragma once
// A part program file read for a machine: the interpreter starts where the machine's program starts (the home
// tool point in program coordinates and its angles), so a first move without some axes keeps them there.
#include <cstdint>
#include <string>
#include <vector>

#include "machine/machine.hpp"
#include "program/canonical_program.hpp"
#include "program/part_program.hpp"

namespace pkm::pipeline {

/// What a command is told about how to read its program, besides the machine (LinuxCNC's [RS274NGC] INI
/// settings and the tool table): every command that reads a program takes the same options.
struct ProgramOptions {
  std::string tool_table_path;               ///< LinuxCNC tool table for G43 (lengths in mm); empty: none
  std::vector<std::string> subroutine_path;  ///< folders searched for `o<name> call` files, in order
  std::string parameter_file;                ///< LinuxCNC .var file read at start; empty: all parameters 0
  bool write_parameter_file = false;         ///< write the parameters back at the program's end
  std::uint64_t max_blocks = 100'000'000;    ///< executed blocks before a program is refused as endless
  /// G-code, or which CAM system's CL data; automatic: decided from the content (docs/cl-data.md).
  program::ProgramFormat format = program::ProgramFormat::automatic;
  bool apply_cl_transforms = true;  ///< CL data: MSYS/CSYS/ROTABL applied (false: the CL frame kept)
};

/// The interpreter's options for `options`, starting at program zero (as `pkm interpret` and rs274 do).
program::InterpretOptions interpret_options(const ProgramOptions& options);

/// interpret_options for `machine`: starting where its programs start, the moves to `sink` if given.
program::InterpretOptions interpret_options_for(const Machine& machine, const ProgramOptions& options,
                                                program::MoveSink sink = {});

/// G-code or CL data (told apart by content, or options.format), read with `options`, starting where the
/// machine's programs start. With a `sink`, the moves go to it as they are read (program/move_output.hpp).
Result<program::CanonicalProgram> load_program_for(const Machine& machine, const std::string& program_path,
                                                   const ProgramOptions& options = {},
                                                   program::MoveSink sink = {});

/// LinuxCNC's SUBROUTINE_PATH is a colon-separated list; the command line also repeats the option. Each
/// given entry is split at ':' and empty pieces dropped, keeping the order.
std::vector<std::string> split_search_path(const std::vector<std::string>& given);

}  // namespace pkm::pipeline
