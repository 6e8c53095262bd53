// load_part_program: picks the reader by the file's content (program_format.hpp), or as the user says.
#include "program/part_program.hpp"

#include "io/text_file.hpp"

namespace pkm::program {

Result<CanonicalProgram> load_part_program(const std::string& path, const InterpretOptions& options) {
  auto text = read_text_file(path, "part program");
  if (!text) return text.error();
  return read_part_program(*text, path, options);
}

Result<CanonicalProgram> read_part_program(std::string_view text, const std::string& path,
                                           const InterpretOptions& options) {
  const ProgramFormat format =
      options.format == ProgramFormat::automatic ? detect_program_format(text) : options.format;
  if (is_cl_format(format)) {
    InterpretOptions cl_options = options;
    cl_options.format = format;
    return read_cl_data(text, path, cl_options);
  }
  return interpret_gcode(text, path, options);
}

}  // namespace pkm::program
