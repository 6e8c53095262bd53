#pragma once
// `pkm modes --map` as one library call: the lowest natural frequency of the machine's elastic struts over a
// plane grid of poses (dynamics/frequency_map.hpp), written as a CSV (formats/frequency_map_csv.hpp).
#include <string>
#include <vector>

#include "dynamics/frequency_map.hpp"
#include "dynamics/pose_grid.hpp"
#include "machine/machine.hpp"

namespace pkm::pipeline {

struct ModesMapJob {
  dynamics::PlaneGrid grid;
  std::string out_path;               ///< the map's CSV; empty: not written
  std::string out_name = "out_path";  ///< how messages about the CSV name it (the CLI: "--out")
};

struct ModesMapJobResult {
  double points_per_axis = 0.0;
  std::vector<Pose> poses;  ///< the grid's, in its order
  std::vector<dynamics::FrequencyMapPoint> points;
  dynamics::FrequencyMapSummary summary;
};

/// A machine without the elastic model is refused before the grid is looked at; then the grid as
/// pipeline::plane_map_grid takes it. Everything is computed before the CSV is touched.
Result<ModesMapJobResult> run_modes_map_job(const Machine& machine, const ModesMapJob& job);

}  // namespace pkm::pipeline
