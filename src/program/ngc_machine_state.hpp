#pragma once
// The modal state of an RS274/NGC program while it runs: what LinuxCNC's interpreter carries from block to
// block. Lengths are mm whatever the program's units (converted when read); the position is the programmed
// (nominal) point in program coordinates.
#include <Eigen/Core>

#include "program/canonical_program.hpp"

namespace pkm::program::ngc {

enum class FeedMode { units_per_minute, inverse_time, units_per_revolution };  // G94 G93 G95

struct MachineState {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();  ///< program coordinates of the programmed point
  Eigen::Vector3d abc_deg = Eigen::Vector3d::Zero();
  int motion = 800;  ///< motion mode, G-code ×10; rs274 starts with G80 (none)
  Plane plane = Plane::xy;
  bool inch = false;  ///< rs274 starts in mm
  bool incremental = false;
  bool arc_centre_incremental = true;  ///< G91.1
  FeedMode feed_mode = FeedMode::units_per_minute;
  double feed = 0.0;          ///< F as written, program units (per minute, per revolution or inverse time)
  bool retract_to_r = false;  ///< G99 (rs274 starts in G98)
  // Tools
  int selected_tool = 0;        ///< T
  int current_tool = 0;         ///< in the spindle (M6, M61)
  double tool_length_mm = 0.0;  ///< G43 offset in effect (Z)
  // The data of the tool in the spindle, copied from the table at M6 and M61 (and by G10 L1/L10/L11 of that
  // tool): G43 without H uses these.
  double spindle_tool_length_mm = 0.0;
  double spindle_tool_diameter_mm = 0.0;
  double tool_diameter_mm = 0.0;
  int tool_length_code = 490;  ///< G43 / G43.1 / G49 in effect, ×10
  // Spindle and coolant
  double spindle_speed = 0.0;
  int spindle_direction = 0;  ///< 1 M3, -1 M4, 0 stopped
  bool css = false;           ///< G96
  bool mist = false, flood = false;
  bool feed_override = true, speed_override = true, adaptive_feed = false, feed_hold = true;
  // Path control
  double path_tolerance_mm = -1.0;
  bool exact_stop = false;
  int path_code = 640;
  // Cutter compensation: 400 G40, 410 G41, 420 G42 (×10; .1 variants kept as 411 / 421)
  int cutter_code = 400;
  int frame_index = 0;  ///< into CanonicalProgram::frames
  WorkFrame frame;

  double mm_per_unit() const { return inch ? 25.4 : 1.0; }
};

}  // namespace pkm::program::ngc
