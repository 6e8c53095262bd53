// libFuzzer harness: load files (--load @FILE.yaml, statics::parse_load_yaml) and the --load key=value text.
// An exception escaping the library ends the run as a crash: bad input must come back as an error.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pkm::fuzz::run_load(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
