#pragma once
// What the benchmarks share: the ch5 hexapod of the shipped examples, loaded once.
#include <filesystem>
#include <stdexcept>

#include "io/machine_file.hpp"

namespace pkm::bench {

/// examples/machines/hexapod_ch5.yaml of the source tree (PKM_SOURCE_DIR), loaded at the first call.
inline const Machine& ch5_hexapod() {
  static const Machine m = [] {
    auto loaded = load_machine_file(
        (std::filesystem::path(PKM_SOURCE_DIR) / "examples/machines/hexapod_ch5.yaml").string());
    if (!loaded) throw std::runtime_error(loaded.error().message);
    return std::move(loaded.value());
  }();
  return m;
}

}  // namespace pkm::bench
