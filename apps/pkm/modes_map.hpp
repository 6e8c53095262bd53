#pragma once
// pkm modes --map: the lowest natural frequency over a plane grid of poses, written as a CSV, with a summary
// on stdout (src/dynamics/frequency_map.hpp does the work; this parses and prints).
#include <string>

namespace pkm::cli {

/// The most grid points a map may have: ~30 µs each on the ch5 hexapod (and ~80 bytes of CSV), so the cap
/// is about half a minute and 80 MB; more is almost always a mistyped step. The message names --step-mm and
/// --range-mm.
inline constexpr double kMaxModesMapPoints = 1'000'000;

struct ModesMapArguments {
  std::string machine_path;
  std::string centre_text;  ///< empty: the machine's home
  std::string plane = "xy";
  double half_range_mm = 200.0;
  double step_mm = 20.0;
  std::string out_path;
  bool json = false;
};

/// Runs the map and returns the exit code; errors are reported as `pkm modes: error: ...`.
int run_modes_map(const ModesMapArguments& arguments);

}  // namespace pkm::cli
