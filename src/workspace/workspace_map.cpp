#include "workspace/workspace_map.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <optional>

#include "dynamics/natural_frequencies.hpp"
#include "stiffness/compliance_model.hpp"
#include "stiffness/stiffness_map.hpp"

namespace pkm::workspace {
namespace {

// What the optional layers need, made once before the cells are computed: the failures that concern the
// machine file (no springs, no dynamics) are reported before any cell is looked at.
struct MapLayers {
  const Machine* machine = nullptr;
  std::optional<dynamics::ElasticModel> elastic;  // immutable: shared by the threads
  const CalibratedErrorAtPose* calibrated_error = nullptr;
  bool stiffness = false;
};

// The compliance model reuses buffers of its own with the frame model (compliance_model.hpp: one per thread),
// so each thread makes its own the first time it needs one.
using ThreadCompliance = tbb::enumerable_thread_specific<std::optional<stiffness::ComplianceModel>>;

void fill_optional_layers(const MapLayers& layers, const Pose& pose, ThreadCompliance& compliance,
                          WorkspaceCell& cell) {
  if (layers.stiffness) {
    std::optional<stiffness::ComplianceModel>& model = compliance.local();
    if (!model) model.emplace(stiffness::ComplianceModel::make(*layers.machine).value());  // checked up front
    if (auto c = model->at(pose); c) {
      cell.lowest_stiffness_N_um = stiffness::lowest_translational_stiffness(*c).lowest_stiffness_N_um;
    }
  }
  if (layers.elastic) {
    if (auto modes = dynamics::natural_modes(*layers.elastic, pose); modes) {
      cell.lowest_frequency_Hz = modes->frequency_Hz[0];
    }
  }
  if (layers.calibrated_error) cell.calibrated_error_mm = (*layers.calibrated_error)(pose);
}

// One cell, the same code on every thread: the map does not depend on which thread computed which cell.
void compute_workspace_cell(const Machine& machine, const GridCells& cells, const MapLayers& layers,
                            ThreadCompliance& compliance, long index, WorkspaceCell& cell) {
  Pose completed;
  evaluate_cell_kinematics(machine, cells.pose(index), cell, completed);
  if (cell.status == CellStatus::ok) fill_optional_layers(layers, completed, compliance, cell);
}

}  // namespace

Result<WorkspaceMap> workspace_map(const Machine& machine, const WorkspaceGrid& grid,
                                   const WorkspaceMapOptions& options) {
  if (Status valid = validate_grid(*machine.mechanism, grid); !valid) return valid.error();
  MapLayers layers;
  layers.machine = &machine;
  if (options.stiffness) {
    auto model = stiffness::ComplianceModel::make(machine);
    if (!model) return model.error();
    layers.stiffness = true;
  }
  if (options.frequencies) {
    auto elastic = dynamics::make_elastic_model(machine);
    if (!elastic) return elastic.error();
    layers.elastic = std::move(*elastic);
  }
  if (options.calibrated_error) layers.calibrated_error = &options.calibrated_error;

  const GridCells cells(grid, machine.mechanism->convention());
  WorkspaceMap map;
  map.grid = grid;
  for (int a = 0; a < cells.axis_count(); ++a) map.points_per_axis.push_back(cells.points(a));
  map.has_stiffness = layers.stiffness;
  map.has_frequencies = layers.elastic.has_value();
  map.has_calibrated_error = layers.calibrated_error != nullptr;
  // Every cell's storage is made here, once: the threads only write into it.
  map.cells.resize(static_cast<std::size_t>(cells.count()));
  ThreadCompliance compliance;
  const auto run = [&](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      compute_workspace_cell(machine, cells, layers, compliance, i, map.cells[static_cast<std::size_t>(i)]);
    }
  };
  if (options.threads == 1) {
    run(0, cells.count());
    return map;
  }
  // More threads than cores would only take turns (and TBB warns that it cannot have them).
  const int cores = tbb::info::default_concurrency();
  tbb::task_arena arena(options.threads > 0 && options.threads < cores ? options.threads : cores);
  arena.execute([&] {
    // A task of at least 16 cells (~0.1 ms on the ch5 hexapod) is long against TBB's cost of scheduling it.
    tbb::parallel_for(tbb::blocked_range<long>(0, cells.count(), 16),
                      [&](const tbb::blocked_range<long>& r) { run(r.begin(), r.end()); });
  });
  return map;
}

}  // namespace pkm::workspace
