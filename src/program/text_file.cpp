#include "program/text_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iterator>

namespace pkm::program {

Result<std::string> read_text_file(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::io, fmt::format("{}: cannot read {}", path, what));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return make_error(ErrorCode::io, fmt::format("{}: error reading {}", path, what));
  return text;
}

}  // namespace pkm::program
