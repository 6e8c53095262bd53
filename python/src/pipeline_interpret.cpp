// pkm.interpret: the canonical moves of a part program, as `pkm interpret --json` prints them.
#include "bindings.hpp"
#include "pipeline/load_program.hpp"
#include "pipeline_bindings.hpp"
#include "pipeline_program_arrays.hpp"
#include "pipeline_support.hpp"
#include "program/part_program.hpp"

namespace pkm::python {

void bind_interpret(py::module_& m) {
  m.def(
      "interpret",
      [](const py::object& program_path, const Machine* machine, const py::object& tool_table,
         const py::object& subroutine_path, const py::object& parameter_file, const std::string& format,
         bool transform) {
        const std::string path = optional_path(program_path);
        pipeline::ProgramOptions options = program_options(tool_table, subroutine_path, parameter_file);
        const auto parsed = program::parse_program_format(format);
        if (!parsed) {
          throw py::value_error("unknown format '" + format + "': one of " +
                                std::string(program::program_format_keys()));
        }
        options.format = *parsed;
        options.apply_cl_transforms = transform;
        Result<program::CanonicalProgram> program = make_error(ErrorCode::bad_input, "not interpreted");
        {
          py::gil_scoped_release released;
          if (machine != nullptr) {
            program = pipeline::load_program_for(*machine, path, options);
          } else {
            program = program::load_part_program(path, pipeline::interpret_options(options));
          }
        }
        return program_arrays(unwrap(std::move(program)));
      },
      py::arg("program_path"), py::arg("machine") = py::none(), py::arg("tool_table") = py::none(),
      py::arg("subroutine_path") = py::none(), py::arg("parameter_file") = py::none(),
      py::arg("format") = "auto", py::arg("transform") = true,
      R"doc(The canonical moves of a part program: G-code, or CL data (NX CLSF, Pro/CLfile, CATIA, SolidWorks CAM /
CAMWorks, APT), told apart by the content whatever the file's name; `format` forces one ("gcode", "apt",
"nx", "creo", "catia", "solidworks"), `transform=False` keeps CL points in the frame MSYS/CSYS/ROTABL give.

Without `machine` the interpreter starts at program zero, as `pkm interpret` does; with a machine it starts
where that machine's programs start (its home tool point in program coordinates, and its A B C), as `pkm plan`
reads the program. `tool_table`: a LinuxCNC tool table for G43 (lengths in mm). `subroutine_path`: folders
searched for `o<name> call` files (a list, or a colon-separated string as LinuxCNC's SUBROUTINE_PATH).
`parameter_file`: a LinuxCNC .var file read at the start (work offsets, G28/G30 positions); not written back.

Returns a dict of arrays, one row per move (M moves):
  line (M,) int32: 1-based line of the main program (the calling line inside a subroutine);
  source_file (M,) int32: index into files of the file the move was written in; source_line (M,) int32;
  kind (M,) str: rapid | line | arc | dwell;
  end_mm (M, 3): end of the tool tip, work coordinates (the program's own plus G54…/G92 offsets);
  end_abc_deg (M, 3): A, B, C at the end, degrees;
  program_end_mm (M, 3): the end as the program wrote it (LinuxCNC's canonical coordinates); frame (M,) int32:
  index into frames, the work offsets in effect (system, g5x_mm, g5x_abc_deg, xy_rotation_deg, g92_mm,
  g92_abc_deg);
  tool_axis_given (M,) bool, tool_axis (M, 3): the programmed unit tool axis (CL data; NaN where not given);
  center_mm, normal (M, 3): arc centre and unit axis (NaN for other moves); turns (M,) int32 (0: no arc);
  feed_mm_min (M,); inverse_time_per_min (M,) (G93; NaN otherwise); dwell_s (M,); tool_length_mm (M,);
  path_tolerance_mm (M,) (G64 P; NaN: none); exact_stop (M,) bool (G61);
and source, format (how it was read: "G-code (RS274/NGC)", "NX CLSF" …), files (the main program, then the subroutine files read), frames, events (list of (line, text)),
start_mm, start_abc_deg, end_line.
Raises pkm.ProgramError (file, line, column) for a malformed program, pkm.FileIOError if it cannot be read.)doc");
}

}  // namespace pkm::python
