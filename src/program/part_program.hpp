#pragma once
// Reading part programs into canonical moves: G-code (RS274/NGC) and APT CL data.
// Every error names the file, line and column: "prog.ngc:12:5: unknown G-code G5.3".
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "program/canonical_program.hpp"
#include "program/move_output.hpp"
#include "program/program_format.hpp"

namespace pkm::program {

struct InterpretOptions {
  /// Where the tool is before the first block (program coordinates); the first incremental move and the
  /// words a first block leaves out are taken from here. rs274 starts at zero.
  Eigen::Vector3d start_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d start_abc_deg = Eigen::Vector3d::Zero();
  /// LinuxCNC-format tool table (`T1 P1 Z25.0 D6 ;comment`) for G43; empty = no table (G43 H>0 is an error).
  std::string tool_table_path;
  /// Skip blocks that start with `/` (the block-delete switch on).
  bool block_delete = true;
  /// Folders searched for subroutine files `<name>.ngc` (LinuxCNC [RS274NGC] SUBROUTINE_PATH).
  std::vector<std::string> subroutine_path;
  /// LinuxCNC parameter file (.var) read at start (work offsets, G28/G30 positions …); empty = none, all
  /// zero.
  std::string parameter_file;
  /// Write the parameters back to parameter_file at the end of the program (atomically), as LinuxCNC does.
  bool write_parameter_file = false;
  /// Bounds that turn a program that never ends into an error at its line.
  std::uint64_t max_blocks = 100'000'000;
  int max_call_depth = 100;
  /// The language, and for CL data the CAM system's dialect; automatic: decided from the content.
  ProgramFormat format = ProgramFormat::automatic;
  /// CL data: turn the points and tool axes from the frame MSYS/CSYS/TRNTYP give into the part frame (false:
  /// keep the CL frame the file is written in).
  bool apply_cl_transforms = true;
  /// Given: each move is handed to it as it is read (one move late, move_output.hpp) and the program's
  /// `moves` stay empty; its error stops the reading.
  MoveSink move_sink;
};

/// G-code (RS274/NGC as CAM post-processors write it). `source_name` is used in messages.
Result<CanonicalProgram> interpret_gcode(std::string_view text, const std::string& source_name,
                                         const InterpretOptions& options = {});

/// APT CL data in the dialect `options.format` names (automatic: recognised from the text; docs/cl-data.md).
Result<CanonicalProgram> read_cl_data(std::string_view text, const std::string& source_name,
                                      const InterpretOptions& options = {});

/// Reads a file and picks the reader by its content (or `options.format`), whatever its extension.
Result<CanonicalProgram> load_part_program(const std::string& path, const InterpretOptions& options = {});

/// The same for a file's text already read (read_text_input's, or a mapped file's); `path` names it.
Result<CanonicalProgram> read_part_program(std::string_view text, const std::string& path,
                                           const InterpretOptions& options = {});

}  // namespace pkm::program
