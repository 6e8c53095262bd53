#include "io/version.hpp"

// PKM_VERSION comes from CMakeLists.txt (this file's own compile definition), so that bumping the version
// recompiles one file.
#ifndef PKM_VERSION
#error "PKM_VERSION must be defined by the build (project(pkm VERSION ...))"
#endif

namespace pkm {

std::string_view pkm_version() {
  return PKM_VERSION;
}

}  // namespace pkm
