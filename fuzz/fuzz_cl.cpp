// libFuzzer harness: APT CL data through its reader (program::read_cl_data), as pkm plan reads a .cl.
// An exception escaping the library ends the run as a crash: bad input must come back as an error.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_entries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pkm::fuzz::run_cl(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
