// A load file belongs to one part program: a block for lines the program does not have is refused.
#include <fmt/format.h>

#include <algorithm>

#include "io/input_file.hpp"
#include "statics/load_model.hpp"

namespace pkm::statics {

Status check_load_lines(const LoadModel& loads, int program_lines, std::string_view program_name) {
  for (const BlockLoad& block : loads.blocks) {
    if (block.first_line <= program_lines) continue;
    const ErrorLocation& at = block.location;
    const std::string lines = block.first_line == block.last_line
                                  ? fmt::format("line {}", block.first_line)
                                  : fmt::format("lines {} to {}", block.first_line, block.last_line);
    Error error =
        make_error(ErrorCode::bad_input,
                   fmt::format("{}:{}:{}: {}: a load for {}, but {} has {} lines: the load would never act",
                               at.file, at.line, at.column, at.key, lines, program_name, program_lines));
    error.location = at;
    return error;
  }
  return ok_status();
}

Status check_load_lines(const LoadModel& loads, const std::string& program_path) {
  if (loads.blocks.empty()) return ok_status();
  auto program = read_text_input(program_path, "part program");
  if (!program) return ok_status();
  // Lines as the program readers count them: a last line without a line end is a line too.
  const std::string& text = *program;
  int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  if (!text.empty() && text.back() != '\n') ++lines;
  return check_load_lines(loads, lines, program_path);
}

}  // namespace pkm::statics
