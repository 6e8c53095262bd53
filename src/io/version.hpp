#pragma once
// The project's version, from CMake's project(pkm VERSION x.y.z): the one place it is set. pkm --version
// prints it; every manifest and summary.json carries it, so a folder says which pkm wrote it.
#include <string_view>

namespace pkm {

/// "0.1.0": the version of the pkm that was built.
std::string_view pkm_version();

}  // namespace pkm
