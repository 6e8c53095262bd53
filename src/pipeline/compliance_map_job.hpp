#pragma once
// `pkm compliance --map` as one library call: the lowest translational stiffness of the strut-only model and
// its direction over a plane grid of poses (stiffness/stiffness_map.hpp), written as a CSV
// (formats/stiffness_csv.hpp).
#include <string>
#include <vector>

#include "core/progress.hpp"
#include "dynamics/pose_grid.hpp"
#include "machine/machine.hpp"
#include "stiffness/stiffness_map.hpp"

namespace pkm::pipeline {

struct ComplianceMapJob {
  dynamics::PlaneGrid grid;
  std::string out_path;               ///< the map's CSV; empty: not written
  std::string out_name = "out_path";  ///< how messages about the CSV name it (the CLI: "--out")
  ProgressSink progress;              ///< told the phase
};

struct ComplianceMapJobResult {
  double points_per_axis = 0.0;
  std::vector<Pose> poses;  ///< the grid's, in its order
  std::vector<stiffness::StiffnessMapPoint> points;
  stiffness::StiffnessMapSummary summary;
};

/// A machine without the struts' stiffness is refused before the grid is looked at; then the grid as
/// pipeline::plane_map_grid takes it. Everything is computed before the CSV is touched.
Result<ComplianceMapJobResult> run_compliance_map_job(const Machine& machine, const ComplianceMapJob& job);

}  // namespace pkm::pipeline
