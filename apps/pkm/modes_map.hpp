#pragma once
// pkm modes --map: the lowest natural frequency over a plane grid of poses, written as a CSV, with a summary
// on stdout (pipeline/modes_map_job.hpp does the work; map_grid.hpp reads the grid; this prints).
#include <string>

#include "map_grid.hpp"

namespace pkm::cli {

struct ModesMapArguments {
  std::string machine_path;
  MapGridArguments grid;
  std::string out_path;
  bool json = false;
};

/// Runs the map and returns the exit code; errors are reported as `pkm modes: error: ...`.
int run_modes_map(const ModesMapArguments& arguments);

}  // namespace pkm::cli
