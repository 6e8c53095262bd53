#pragma once
// Shared helpers for the tests: machine files from strings, seeded random poses and geometries.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "machine/machine_file.hpp"

namespace pkm::test {

/// Parses a machine file given as text; fails the test (fatally) with the loader's message on error.
inline Machine machine_from_text(const std::string& yaml, const std::string& name = "test.yaml") {
  auto machine = parse_machine_text(yaml, name);
  if (!machine) {
    ADD_FAILURE() << machine.error().message;
    throw std::runtime_error(machine.error().message);
  }
  return std::move(machine.value());
}

inline Machine machine_from_example(const std::string& relative_path) {
  auto machine = load_machine_file(std::string(PKM_SOURCE_DIR) + "/" + relative_path);
  if (!machine) {
    ADD_FAILURE() << machine.error().message;
    throw std::runtime_error(machine.error().message);
  }
  return std::move(machine.value());
}

/// Uniform in [lo, hi].
inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

}  // namespace pkm::test
