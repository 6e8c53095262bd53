#pragma once
// The plane grid of poses a map is computed over, from the command line: `pkm modes --map` and
// `pkm compliance --map` take the same --centre, --plane, --range-mm and --step-mm and refuse the same
// inputs (dynamics/pose_grid.hpp builds the grid).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "dynamics/pose_grid.hpp"
#include "machine/mechanism.hpp"

namespace pkm::cli {

/// The most grid points a map may have: ~30 µs each on the ch5 hexapod (and ~80 bytes of CSV), so the cap
/// is about half a minute and 80 MB; more is almost always a mistyped step. The message names --step-mm and
/// --range-mm.
inline constexpr double kMaxMapGridPoints = 1'000'000;

struct MapGridArguments {
  std::string centre_text;  ///< empty: the machine's home
  std::string plane = "xy";
  double half_range_mm = 200.0;
  double step_mm = 20.0;
};

/// Adds --centre (--center), --range-mm, --step-mm and --plane to `command`, each needing `map_flag`.
void add_map_grid_options(CLI::App& command, MapGridArguments& arguments, CLI::Option* map_flag);

struct MapGrid {
  dynamics::PlaneGrid grid;
  double points_per_axis = 0.0;
  std::vector<Pose> poses;
};

/// The grid of `arguments` for `mechanism`. Errors (bad_input) name the flag: a centre that is no pose, a
/// plane a planar machine cannot move in, more than kMaxMapGridPoints points.
Result<MapGrid> map_grid_poses(const Mechanism& mechanism, const MapGridArguments& arguments);

/// "x, y, z, a1, a2, a3" of a pose, as --pose takes it.
std::string map_pose_text(const Mechanism& mechanism, const Pose& pose);

}  // namespace pkm::cli
