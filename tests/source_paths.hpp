#pragma once
// Paths of the source tree and of the pkm binary, for tests.
//
// Defined out of line with std::filesystem: GCC 12 inlines `std::string(LITERAL) + "/" + x` and reports a
// false -Warray-bounds for some lengths of the checkout path, which would make the build depend on where it
// is cloned.
#include <string>
#include <string_view>

namespace pkm::test {

/// `relative` (for example "examples/machines/hexapod_ch5.yaml") under the project's source directory.
std::string source_path(std::string_view relative);

/// The pkm command-line binary built next to the tests.
std::string pkm_binary_path();

}  // namespace pkm::test
