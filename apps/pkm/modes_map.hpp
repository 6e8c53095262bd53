#pragma once
// pkm modes --map: the lowest natural frequency over a plane grid of poses, written as a CSV, with a summary
// on stdout (src/dynamics/frequency_map.hpp does the work; map_grid.hpp reads the grid; this prints).
#include <string>

#include "map_grid.hpp"

namespace pkm::cli {

/// The most grid points a map may have (map_grid.hpp: shared with `pkm compliance --map`).
inline constexpr double kMaxModesMapPoints = kMaxMapGridPoints;

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
