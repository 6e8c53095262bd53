#pragma once
// Where to put the workpiece (Smirnov 2019, §3.8.1, Fig. 120): the same path under the same loads takes a
// different drive energy at different places in the workspace, because the drives' gearing to the tool
// (the Jacobian) changes with the pose. The program is moved along Z so that its first plane lies at each of
// the heights asked, the platform's angles are held as programmed, and at every point the drive forces that
// hold the load and the weights (statics, (91)) and the drive energy of each step Σ_j |ΔL_j P_j| (86) are
// summed, per plane and in all. A plane is a run of feed moves ending at one Z: a forming program's circle
// with the step down into it (a helical turn with the step that follows it).
#include <limits>
#include <optional>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "program/canonical_program.hpp"
#include "redundancy/law.hpp"
#include "redundancy/step_minimiser.hpp"
#include "statics/load_model.hpp"

namespace pkm::redundancy {

struct PlacementOptions {
  std::vector<double> z1_mm;  ///< the heights of the first plane to try, program coordinates
  double step_mm = 2.0;       ///< the path step the energy is summed over
  statics::LoadModel loads;
  EnergyAccounting accounting = EnergyAccounting::no_recovery;
  /// Also the energy with the platform's angles chosen by this law (the seeds: the energy law), greedy along
  /// each plane from the programmed angles, to which they return at the start of every plane (§3.8.1).
  std::optional<Law> law;
  FreeBounds law_bounds_deg;  ///< the angles' bounds (the seeds: ψ, ϑ within ±5°, γ within ±20°)
  GreedySettings greedy;
};

struct PlaneEnergy {
  double z_mm = 0.0;  ///< program coordinates, as placed
  int first_line = 0;
  double energy_J = 0.0;                                           ///< the angles held
  double law_energy_J = std::numeric_limits<double>::quiet_NaN();  ///< chosen by the law (NaN: not asked)
};

struct Placement {
  double z1_mm = 0.0;
  double offset_mm = 0.0;  ///< the program moved this far along Z
  bool feasible = true;    ///< every point reachable within the limits
  int first_infeasible_line = 0;
  double energy_J = 0.0;         ///< the drives', in the accounting asked
  double required_work_J = 0.0;  ///< |work of the loads and the weights| along the path, (87)
  double peak_force_N = 0.0;
  std::vector<PlaneEnergy> planes;  ///< in program order (feed moves; the rapids count in the total only)
  double law_energy_J = std::numeric_limits<double>::quiet_NaN();  ///< with PlacementOptions::law
};

/// The program's first plane: the Z where its first feed move ends (the plunge to the sheet).
Result<double> first_plane_z_mm(const program::CanonicalProgram& program);

/// The study at every height; errors name the program (no feed move, tool-length offsets) or the machine (no
/// angles to hold: a mechanism whose orientation follows its position).
Result<std::vector<Placement>> placement_study(const program::CanonicalProgram& program,
                                               const Machine& machine, const PlacementOptions& options);

}  // namespace pkm::redundancy
