// load_part_program: picks the reader by the file's extension.
#include "program/part_program.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "program/text_file.hpp"

namespace pkm::program {

namespace {

bool is_cl_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".cl" || extension == ".cls" || extension == ".apt";
}

}  // namespace

Result<CanonicalProgram> load_part_program(const std::string& path, const InterpretOptions& options) {
  auto text = read_text_file(path, "part program");
  if (!text) return text.error();
  if (is_cl_extension(path)) return read_cl_data(*text, path, options);
  return interpret_gcode(*text, path, options);
}

}  // namespace pkm::program
