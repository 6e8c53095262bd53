#pragma once
// Process loads along a path: a cutting force split along the direction of travel (Smirnov's P_τ and P_n,
// §3.1 and §3.4.2), an axial force, the moment of the tangential force at the cutter edge, and a
// constant extra load; per program line ranges. The CLI's --load and load files (docs/statics.md) build a
// LoadModel.
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "core/pose.hpp"
#include "core/result.hpp"
#include "statics/wrench.hpp"

namespace pkm::statics {

/// Where on the path a load is wanted.
struct LoadPoint {
  /// Unit direction of travel, base frame; zero for a point that does not move (only the constant load acts).
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();
  /// Unit tool axis, base frame, from the tool tip towards the spindle.
  Eigen::Vector3d tool_axis = Eigen::Vector3d::UnitZ();
  int line = 0;         ///< program line, to pick a BlockLoad
  bool cutting = true;  ///< false on rapids: no cutting load, only the constant one
};

/// The load point of a platform at `pose` travelling with the tool point's `velocity_mm_s` (zero: at rest,
/// no direction of travel): the tool axis is `tool_axis_platform` (platform frame) turned with the pose.
LoadPoint travel_load_point(const Pose& pose, const Eigen::Vector3d& velocity_mm_s,
                            const Eigen::Vector3d& tool_axis_platform, int line, bool cutting);

/// One load case, all forces acting on the tool (so on the platform), base frame.
/// With t the tangent, a the tool axis and n = unit(a × t) (to the left of travel seen from the spindle):
///   F = −tangential_N t + normal_N n + axial_N a + force_N,
///   M = (cutter_radius_mm · c) × (−tangential_N t) + moment_Nmm,  c = contact_side · n,
/// i.e. the tangential force acts at the cutter edge (§3.4.2: M = P_τ R_Ф), normal and axial forces through
/// the tool point. When t is parallel to a (a plunge) n is undefined: the normal force and the moment of the
/// tangential force are left out.
struct CuttingLoad {
  double tangential_N = 0;      ///< resists the feed: force on the tool −tangential_N · t
  double normal_N = 0;          ///< force on the tool +normal_N · n
  double axial_N = 0;           ///< force on the tool +axial_N · a (pushes the tool back into the spindle)
  double cutter_radius_mm = 0;  ///< lever of the tangential force from the tool point
  int contact_side = +1;  ///< +1: the cutter touches the work on its left (c = +n); −1: right (c = −n)
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();     ///< constant extra force, base frame
  Eigen::Vector3d moment_Nmm = Eigen::Vector3d::Zero();  ///< constant extra moment about the tool point

  bool is_zero() const;
};

/// A load for the program lines first_line..last_line (inclusive).
struct BlockLoad {
  int first_line = 0;
  int last_line = 0;
  CuttingLoad load;
  ErrorLocation location{};  ///< where the load file gives the lines (file, line, column, key), for messages
};

class LoadModel {
 public:
  CuttingLoad default_load;
  std::vector<BlockLoad> blocks;  ///< later entries win where line ranges overlap
  /// The blocks are disjoint and in ascending line order (a per-line CSV file): looked up by bisection, so
  /// that a load per line of a 100 000-line program costs no more than one per block.
  bool blocks_ascending = false;

  /// The load case of a program line: the last block containing it, else default_load.
  const CuttingLoad& load_for_line(int line) const;
  /// The wrench on the platform at a path point, moment about the tool point.
  Wrench wrench_at(const LoadPoint& point) const;
  /// True when no load is ever applied (every case zero).
  bool empty() const;
};

/// The wrench of one load case at a point (see CuttingLoad).
Wrench cutting_wrench(const CuttingLoad& load, const LoadPoint& point);

/// The CLI's --load: either comma-separated key=value pairs
///   tangential=N, normal=N, axial=N, cutter_radius=MM, contact=left|right, force=FX:FY:FZ, moment=MX:MY:MZ
/// (the default load; e.g. "tangential=1000,normal=100,cutter_radius=5"), or "@FILE" for a YAML load file
/// (parse_load_yaml). Errors (bad_input; io for an unreadable file) quote the offending text.
Result<LoadModel> parse_load_spec(std::string_view spec);

/// A per-line CSV load file (ending in .csv; docs/statics.md): a header `line,` then any of fx_N fy_N fz_N
/// mx_Nmm my_Nmm mz_Nmm tangential_N normal_N axial_N, one row per program line in ascending order. Errors
/// name source:line:column and the column.
Result<LoadModel> parse_load_csv(std::string_view text, const std::string& source_name);

/// Refuses a block for lines the program does not have (it starts after the program's last line,
/// `program_lines`): its load would never act, and a load file for another program would pass unnoticed.
/// The error names the block's place in the load file and the program.
Status check_load_lines(const LoadModel& loads, int program_lines, std::string_view program_name);

/// check_load_lines against the part program at `program_path`, read again here for its line count (a
/// program that cannot be read passes: its reader reports it).
Status check_load_lines(const LoadModel& loads, const std::string& program_path);

/// A YAML load file:  default: {KEY: VALUE, ...}  and  blocks: [{lines: [FIRST, LAST], KEY: VALUE, ...}, ...]
/// with the keys of parse_load_spec (force and moment as [x, y, z], contact as left or right). A block starts
/// from the default's values. Errors name source:line:column and the key.
Result<LoadModel> parse_load_yaml(const std::string& text, const std::string& source_name);

}  // namespace pkm::statics
