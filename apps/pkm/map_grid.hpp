#pragma once
// The plane grid of poses a map is computed over, from the command line: `pkm modes --map` and
// `pkm compliance --map` take the same --centre, --plane, --range-mm and --step-mm and refuse the same
// inputs (dynamics/pose_grid.hpp builds the grid).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dynamics/map_point_counts.hpp"
#include "dynamics/pose_grid.hpp"
#include "machine/machine.hpp"
#include "machine/mechanism.hpp"
#include "pipeline/plane_map_grid.hpp"

namespace pkm::cli {

/// The most grid points a map may have (the library's cap); the message names --step-mm and --range-mm.
inline constexpr double kMaxMapGridPoints = pipeline::kMaxMapGridPoints;

struct MapGridArguments {
  std::string centre_text;  ///< empty: the machine's home
  std::string plane = "xy";
  double half_range_mm = 200.0;
  double step_mm = 20.0;
};

/// Adds --centre (--center), --range-mm, --step-mm and --plane to `command`, each needing `map_flag`.
void add_map_grid_options(CLI::App& command, MapGridArguments& arguments, CLI::Option* map_flag);

/// The grid of `arguments` for `mechanism`, checked before the job takes it so that the messages (bad_input)
/// name the flag: a centre that is no pose, a plane a planar machine cannot move in, more than
/// kMaxMapGridPoints points.
Result<dynamics::PlaneGrid> map_plane_grid(const Mechanism& mechanism, const MapGridArguments& arguments);

/// The JSON fields every map prints (--json): the machine, the output file, the grid, how many points have a
/// value (under `with_value_key`) and why the others have none, and "min_pose"/"max_pose", the poses of the
/// lowest and highest values (null without any). The caller adds its values.
nlohmann::json map_summary_json(const Machine& machine, const dynamics::PlaneGrid& grid, int points_per_axis,
                                const std::vector<Pose>& poses, const dynamics::MapPointCounts& counts,
                                const std::string& with_value_key, const std::string& out_path);

/// "x, y, z, a1, a2, a3" of a pose, as --pose takes it.
std::string map_pose_text(const Mechanism& mechanism, const Pose& pose);

}  // namespace pkm::cli
