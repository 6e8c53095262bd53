#pragma once
// Which language a part program is written in, and for CL data which CAM system's dialect: decided from the
// file's content (never its name), or forced by the user (--format). The dialect decides conventions the
// statements themselves do not state, above all which way a CIRCLE record turns (docs/cl-data.md).
#include <optional>
#include <string_view>

namespace pkm::program {

enum class ProgramFormat {
  automatic,   ///< decide from the content
  gcode,       ///< RS274/NGC as LinuxCNC reads it
  apt,         ///< APT CL data of no known CAM system (ISO 4343 / generic CL print)
  nx,          ///< Siemens NX CLSF
  creo,        ///< PTC Creo / Pro/ENGINEER Pro/CLfile
  catia,       ///< Dassault CATIA APT
  solidworks,  ///< SolidWorks CAM / CAMWorks APT
};

/// The key the user types (`--format nx`): automatic → "auto".
std::string_view program_format_key(ProgramFormat format);
/// The name shown in summaries: "NX CLSF", "G-code (RS274/NGC)".
std::string_view program_format_name(ProgramFormat format);
/// The format of a key ("auto", "gcode", "apt", "nx", "creo", "catia", "solidworks"), case as written.
std::optional<ProgramFormat> parse_program_format(std::string_view key);
/// Every key, for help texts: "auto, gcode, apt, nx, creo, catia, solidworks".
std::string_view program_format_keys();

/// True for the CL dialects (apt, nx, creo, catia, solidworks).
bool is_cl_format(ProgramFormat format);

/// The format of a program from its first statements: CL data (and which CAM system wrote it) or G-code.
/// Never returns automatic. A text with nothing decisive (empty, comments only) is G-code.
ProgramFormat detect_program_format(std::string_view text);

}  // namespace pkm::program
