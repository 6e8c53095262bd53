// The executor's checks of a block's words against what its codes use, with LinuxCNC's reasons.
#include <fmt/format.h>

#include <cmath>

#include "program/ngc_executor.hpp"
#include "program/ngc_executor_support.hpp"

namespace pkm::program::ngc {

using namespace executor_support;

Status Executor::check_words(const gcode::Block& b, int motion, bool moves) const {
  const gcode::Code& non_modal = b.g[gcode::g_non_modal];
  const bool axis_users = codes_take_axis_words(b);
  // Axis words need a motion mode (or G10, G28, G30, G52, G92) to use them.
  if (const int axis_column = b.first_axis_column(); axis_column > 0 && motion == 800 && !axis_users) {
    if (b.g[gcode::g_motion].given())
      return gcode::error_at(where(), axis_column, "axis words with G80 (motion cancelled)");
    return gcode::error_at(where(), axis_column, "axis words without a motion mode (G0, G1, G2 or G3)");
  }
  if (non_modal.is(530) && !(moves && (motion == 0 || motion == 10)))
    return gcode::error_at(where(), non_modal.column, "G53 needs a G0 or G1 move in its block");
  if (auto letters = check_letter_users(b, motion, moves); !letters) return letters;
  if (b['F'].given() && b['F'].value < 0.0)
    return gcode::error_at(where(), b['F'].column, "negative feed rate F");
  if (b['S'].given() && b['S'].value < 0.0)
    return gcode::error_at(where(), b['S'].column, "negative spindle speed S");
  for (const char letter : {'T', 'H'}) {
    const gcode::Value& v = b[letter];
    if (v.given() && (v.value < 0.0 || v.value > kLargestCount || !is_whole(v.value)))
      return gcode::error_at(where(), v.column,
                             fmt::format("{} must be a whole number from 0 to 1000000", letter));
  }
  return ok_status();
}

// Each of I J K R P H D L Q needs a code in its block that uses it.
Status Executor::check_letter_users(const gcode::Block& b, int motion, bool moves) const {
  const gcode::Code& non_modal = b.g[gcode::g_non_modal];
  const bool g10 = non_modal.is(100);
  const bool cycle = moves && is_cycle(motion);
  for (const char letter : {'I', 'J', 'K', 'R'}) {
    const bool used = (moves && is_arc(motion)) || cycle || (g10 && letter == 'R');
    if (b[letter].given() && !used)
      return gcode::error_at(where(), b[letter].column,
                             fmt::format("{} word with no G2 or G3 to use it", letter));
  }
  const bool dwell = non_modal.is(40);
  const bool blend = b.g[gcode::g_path_control].is(640);
  const bool turns = moves && is_arc(motion);
  const bool other_p_user = g10 || cycle || b.m[gcode::m_io].given() || b.m[gcode::m_user].given() ||
                            b.m[gcode::m_override].given() || b.g[gcode::g_cutter].given();
  if (b['P'].given()) {
    const int users = static_cast<int>(dwell) + static_cast<int>(blend) + static_cast<int>(turns);
    if (users == 0 && !other_p_user)
      return gcode::error_at(where(), b['P'].column, "P word with no G2, G3, G4 or G64 to use it");
    if (users > 1)
      return gcode::error_at(where(), b['P'].column, "P word claimed by more than one of G2/G3, G4 and G64");
  }
  if (dwell && !b['P'].given())
    return gcode::error_at(where(), non_modal.column, "G4 without a P word (dwell seconds)");
  const gcode::Code& length = b.g[gcode::g_tool_length];
  if (b['H'].given() && !(length.is(430) || length.is(432)))
    return gcode::error_at(where(), b['H'].column, "H word without G43 or G43.2 to use it");
  if (b['D'].given() && !(b.g[gcode::g_cutter].given() && !b.g[gcode::g_cutter].is(400)))
    return gcode::error_at(where(), b['D'].column, "D word without G41, G42, G41.1 or G42.1 to use it");
  if (b['L'].given() && !(g10 || cycle || b.m[gcode::m_io].given()))
    return gcode::error_at(where(), b['L'].column, "L word with no G10, canned cycle or M66 to use it");
  if (b['Q'].given() &&
      !(cycle || b.m[gcode::m_io].given() || b.m[gcode::m_user].given() || b.m[gcode::m_tool_change].is(610)))
    return gcode::error_at(where(), b['Q'].column,
                           "Q word with no canned cycle, M61, M66 or user M-code to use it");
  return ok_status();
}

// LinuxCNC's predefined named parameters, answered from the state (units: the program's).
std::optional<double> Executor::predefined(std::string_view name) const {
  const double unit = state_.mm_per_unit();
  static constexpr std::string_view kAxes[6] = {"_x", "_y", "_z", "_a", "_b", "_c"};
  for (int i = 0; i < 6; ++i)
    if (name == kAxes[i]) return i < 3 ? state_.position_mm[i] / unit : state_.abc_deg[i - 3];
  if (name == "_u" || name == "_v" || name == "_w") return 0.0;
  auto flag = [](bool b) { return b ? 1.0 : 0.0; };
  if (name == "_metric") return flag(!state_.inch);
  if (name == "_imperial") return flag(state_.inch);
  if (name == "_absolute") return flag(!state_.incremental);
  if (name == "_incremental") return flag(state_.incremental);
  if (name == "_inverse_time") return flag(state_.feed_mode == FeedMode::inverse_time);
  if (name == "_units_per_minute") return flag(state_.feed_mode == FeedMode::units_per_minute);
  if (name == "_units_per_rev") return flag(state_.feed_mode == FeedMode::units_per_revolution);
  if (name == "_coord_system") {
    static constexpr int kCodes[9] = {540, 550, 560, 570, 580, 590, 591, 592, 593};
    return kCodes[state_.frame.system - 1];
  }
  if (name == "_tool_offset") return flag(state_.tool_length_code != 490);
  if (name == "_retract_r") return flag(state_.retract_to_r);
  if (name == "_retract_old_z") return flag(!state_.retract_to_r);
  if (name == "_spindle_rpm_mode") return flag(!state_.css);
  if (name == "_spindle_css_mode") return flag(state_.css);
  if (name == "_ijk_absolute_mode") return flag(!state_.arc_centre_incremental);
  if (name == "_lathe_diameter_mode") return 0.0;
  if (name == "_lathe_radius_mode") return 1.0;
  if (name == "_spindle_on") return flag(state_.spindle_direction != 0);
  if (name == "_spindle_cw") return flag(state_.spindle_direction >= 0);
  if (name == "_mist") return flag(state_.mist);
  if (name == "_flood") return flag(state_.flood);
  if (name == "_speed_override") return flag(state_.speed_override);
  if (name == "_feed_override") return flag(state_.feed_override);
  if (name == "_adaptive_feed") return flag(state_.adaptive_feed);
  if (name == "_feed_hold") return flag(state_.feed_hold);
  if (name == "_feed") return state_.feed / unit;
  if (name == "_rpm") return state_.spindle_speed;
  if (name == "_current_tool" || name == "_current_pocket") return state_.current_tool;
  if (name == "_selected_tool" || name == "_selected_pocket") return state_.selected_tool;
  if (name == "_motion_mode") return state_.motion;
  if (name == "_plane") return state_.plane == Plane::xy ? 170 : (state_.plane == Plane::zx ? 180 : 190);
  if (name == "_ccomp") return state_.cutter_code;
  if (name == "_line") return line_;
  if (name == "_task") return 0.0;  // not running under LinuxCNC's task (as rs274 standalone)
  if (name == "_vmajor") return 2.0;
  if (name == "_vminor") return 9.0;
  return std::nullopt;
}

}  // namespace pkm::program::ngc
