#include "io/text_file.hpp"

#include "io/input_file.hpp"

namespace pkm {

Result<std::string> read_text_file(const std::string& path, const char* what) {
  return read_text_input(path, what);
}

}  // namespace pkm
