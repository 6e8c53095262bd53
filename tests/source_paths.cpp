#include "source_paths.hpp"

#include <filesystem>

namespace pkm::test {

std::string source_path(std::string_view relative) {
  return (std::filesystem::path(PKM_SOURCE_DIR) / std::filesystem::path(relative)).string();
}

std::string pkm_binary_path() {
  return std::filesystem::path(PKM_BINARY).string();
}

}  // namespace pkm::test
