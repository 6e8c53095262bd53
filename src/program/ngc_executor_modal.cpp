// The executor's modal settings: feed and speed, tools, spindle and the other M-codes, plane, cutter radius
// compensation, tool length, coordinate system and path control.
#include <fmt/format.h>

#include <cmath>

#include "program/ngc_executor.hpp"
#include "program/ngc_executor_support.hpp"
#include "program/ngc_work_offsets.hpp"

namespace pkm::program::ngc {

using namespace executor_support;

Status Executor::read_feed_and_speed(const gcode::Block& b) {
  // Units first: F and every length in this block are read in the units the block ends up in.
  if (const gcode::Code& units = b.g[gcode::g_units]; units.given()) {
    const bool inch = units.is(200);
    state_.inch = inch;
    compensation_.set_inch(inch);
  }
  if (const gcode::Code& mode = b.g[gcode::g_feed_mode]; mode.given()) {
    state_.feed_mode = mode.is(930)   ? FeedMode::inverse_time
                       : mode.is(950) ? FeedMode::units_per_revolution
                                      : FeedMode::units_per_minute;
    state_.feed = 0.0;  // rs274 clears the feed on G93, G94 and G95: the next feed move needs an F
  }
  if (b['F'].given() && state_.feed_mode != FeedMode::inverse_time)
    state_.feed = b['F'].value * state_.mm_per_unit();
  if (b['S'].given()) {
    state_.spindle_speed = b['S'].value;
    const gcode::Code& spindle = b.m[gcode::m_spindle];
    if (!spindle.given() || spindle.is(50)) add_event(fmt::format("S{}", state_.spindle_speed));
  }
  return ok_status();
}

Status Executor::tools_and_spindle(const gcode::Block& b) {
  const gcode::Code& tool_change = b.m[gcode::m_tool_change];
  if (b['T'].given()) {
    const int tool = whole(b['T'].value);
    if (tools_ && tool > 0 && !tools_->find(tool))
      return gcode::error_at(
          where(), b['T'].column,
          fmt::format("tool T{} is not in the tool table {}", tool, options_.tool_table_path));
    state_.selected_tool = tool;
    if (!tool_change.given()) add_event(fmt::format("T{}", tool));
  }
  for (int group : {gcode::m_io}) {
    if (const gcode::Code& code = b.m[static_cast<std::size_t>(group)]; code.given()) {
      std::string what = gcode::code_name('M', code.number);
      for (const char letter : {'P', 'E', 'L', 'Q'})
        if (b[letter].given()) what += fmt::format(" {}{}", letter, b[letter].value);
      add_event(std::move(what));
      // Offline there is no input to wait for: M66 reads as LinuxCNC's "timed out" (-1).
      if (code.is(660)) parameters_.set(5399, -1.0);
    }
  }
  if (tool_change.given() && compensation_.active())
    return gcode::error_at(where(), tool_change.column,
                           "Cannot change tools with cutter radius compensation on");
  if (tool_change.is(60)) {
    state_.current_tool = state_.selected_tool;
    add_event(fmt::format("M6 T{}", state_.current_tool));
  } else if (tool_change.is(610)) {
    if (!b['Q'].given())
      return gcode::error_at(where(), tool_change.column, "M61 needs a Q word (tool number)");
    if (whole(b['Q'].value) < 0 || !is_whole(b['Q'].value))
      return gcode::error_at(where(), b['Q'].column, "M61 Q must be a tool number (a whole number ≥ 0)");
    state_.current_tool = whole(b['Q'].value);
    add_event(fmt::format("M61 Q{}", state_.current_tool));
  }
  if (tool_change.given()) {
    const ToolEntry* entry = tools_ ? tools_->find(state_.current_tool) : nullptr;
    state_.spindle_tool_length_mm = entry ? entry->length_mm : 0.0;
    state_.spindle_tool_diameter_mm = entry ? entry->diameter_mm : 0.0;
    parameters_.set(parameter::tool_number, state_.current_tool);
    parameters_.set(parameter::tool_diameter, state_.spindle_tool_diameter_mm);
  }
  const gcode::Code& spindle = b.m[gcode::m_spindle];
  if (spindle.is(30) || spindle.is(40)) {
    state_.spindle_direction = spindle.is(30) ? 1 : -1;
    add_event(fmt::format("{} S{}", spindle.is(30) ? "M3" : "M4", state_.spindle_speed));
  }
  if (spindle.is(50)) {
    state_.spindle_direction = 0;
    add_event("M5");
  }
  if (spindle.is(190)) add_event("M19");
  return ok_status();
}

// State save/restore, coolant, overrides and user M-codes: events (with their words), and the state.
void Executor::machine_functions(const gcode::Block& b) {
  save_or_restore_state(b);
  if (const gcode::Code& coolant = b.m[gcode::m_coolant]; coolant.given()) {
    if (coolant.is(70)) state_.mist = true;
    if (coolant.is(80)) state_.flood = true;
    if (coolant.is(90)) state_.mist = state_.flood = false;
    add_event(gcode::code_name('M', coolant.number));
  }
  if (const gcode::Code& override = b.m[gcode::m_override]; override.given()) {
    const bool on =
        override.is(480) || ((override.is(500) || override.is(510) || override.is(520) || override.is(530)) &&
                             (!b['P'].given() || b['P'].value != 0.0));
    if (override.is(480) || override.is(490)) state_.feed_override = state_.speed_override = on;
    if (override.is(500)) state_.feed_override = on;
    if (override.is(510)) state_.speed_override = on;
    if (override.is(520)) state_.adaptive_feed = on;
    if (override.is(530)) state_.feed_hold = on;
    add_event(gcode::code_name('M', override.number));
  }
  if (const gcode::Code& user = b.m[gcode::m_user]; user.given()) {
    std::string what = gcode::code_name('M', user.number);
    for (const char letter : {'P', 'Q'})
      if (b[letter].given()) what += fmt::format(" {}{}", letter, b[letter].value);
    add_event(std::move(what));
  }
}

// M70 saves the modal state, M72 restores it, M71 forgets it; M73 saves it (LinuxCNC also restores it when
// the subroutine returns; pkm restores it only on M72).
void Executor::save_or_restore_state(const gcode::Block& b) {
  const gcode::Code& code = b.m[gcode::m_state];
  if (!code.given()) return;
  if (code.is(700) || code.is(730)) saved_state_ = state_;
  if (code.is(710)) saved_state_.reset();
  if (code.is(720) && saved_state_) {
    // The position, tools and offsets are not part of the saved state; the modes are.
    MachineState restored = *saved_state_;
    restored.position_mm = state_.position_mm;
    restored.abc_deg = state_.abc_deg;
    restored.selected_tool = state_.selected_tool;
    restored.current_tool = state_.current_tool;
    restored.tool_length_mm = state_.tool_length_mm;
    restored.tool_length_code = state_.tool_length_code;
    restored.frame = state_.frame;
    restored.frame_index = state_.frame_index;
    restored.cutter_code = state_.cutter_code;
    state_ = restored;
  }
  add_event(gcode::code_name('M', code.number));
}

double Executor::tool_diameter_of(int tool) const {
  if (!tools_ || tool <= 0) return 0.0;
  const ToolEntry* entry = tools_->find(tool);
  return entry ? entry->diameter_mm : 0.0;
}

Status Executor::set_plane_and_compensation(const gcode::Block& b) {
  if (const gcode::Code& plane = b.g[gcode::g_plane]; plane.given()) {
    const Plane next = plane.is(170) ? Plane::xy : (plane.is(180) ? Plane::zx : Plane::yz);
    if (auto selected = compensation_.select_plane(next, where(), plane.column); !selected) return selected;
    state_.plane = next;
  }
  const gcode::Code& cutter = b.g[gcode::g_cutter];
  if (!cutter.given()) return ok_status();
  if (cutter.is(400)) {
    state_.cutter_code = 400;
    return compensation_.stop(where(), cutter.column);
  }
  const bool dynamic = cutter.is(411) || cutter.is(421);
  double radius_mm = 0.0;
  const gcode::Value& d = b['D'];
  if (dynamic) {
    if (!d.given())
      return gcode::error_at(
          where(), cutter.column,
          fmt::format("{} needs a D word (tool diameter)", gcode::code_name('G', cutter.number)));
    radius_mm = d.value * state_.mm_per_unit() / 2.0;
  } else {
    const int tool = d.given() ? whole(d.value) : state_.current_tool;
    if (d.given() && (d.value < 0.0 || std::abs(d.value - tool) > 1e-6))
      return gcode::error_at(where(), d.column, "D word must be a tool number (a whole number ≥ 0)");
    if (d.given() && tools_ && tool > 0 && !tools_->find(tool))
      return gcode::error_at(
          where(), d.column,
          fmt::format("tool D{} is not in the tool table {}", tool, options_.tool_table_path));
    radius_mm = tool_diameter_of(tool) / 2.0;
  }
  state_.cutter_code = cutter.number;
  const CompensationSide side =
      (cutter.is(410) || cutter.is(411)) ? CompensationSide::left : CompensationSide::right;
  return compensation_.start(side, radius_mm, state_.plane, where(), cutter.column);
}

Status Executor::set_tool_length(const gcode::Block& b) {
  const gcode::Code& code = b.g[gcode::g_tool_length];
  double length_mm = 0.0;
  auto table_length = [&](int tool, int column, double& out) -> Status {
    out = 0.0;
    if (tool <= 0 || !tools_) return ok_status();  // without a table, tools have zero length (as rs274)
    const ToolEntry* entry = tools_->find(tool);
    if (!entry)
      return gcode::error_at(
          where(), column,
          fmt::format("tool {} is not in the tool table {}", tool, options_.tool_table_path));
    out = entry->length_mm;
    return ok_status();
  };
  const gcode::Value& h = b['H'];
  const int column = h.given() ? h.column : code.column;
  if (code.is(430) || code.is(432)) {
    // As LinuxCNC: G43 without H, or with H0, takes the tool in the spindle; G43.2 adds to what is in effect.
    const bool with_h = h.given() && whole(h.value) > 0;
    const int tool = with_h ? whole(h.value) : state_.current_tool;
    if (code.is(432) && !h.given())
      return gcode::error_at(where(), code.column, "G43.2 needs an H word (tool number)");
    if (!tools_ && tool > 0 && !no_table_noted_) {
      program_->notes.push_back(
          fmt::format("{}:{}: G43 for tool {} without a tool table: tools have zero length (as in rs274)",
                      *file_name_, line_, tool));
      no_table_noted_ = true;
    }
    if (with_h) {
      if (auto read = table_length(tool, column, length_mm); !read) return read;
    } else {
      length_mm = state_.spindle_tool_length_mm;
    }
    if (code.is(432)) length_mm += state_.tool_length_mm;
  } else if (code.is(431)) {
    for (const char letter : {'X', 'Y', 'A', 'B', 'C'})
      if (b[letter].given() && b[letter].value != 0.0)
        return gcode::error_at(
            where(), b[letter].column,
            "G43.1 offsets other than Z are not supported (pkm applies tool length along Z)");
    length_mm = b['Z'].given() ? b['Z'].value * state_.mm_per_unit() : 0.0;
  }
  // As rs274: the tool tip stays where it is, so its program Z changes by the change of offset.
  state_.position_mm.z() -= length_mm - state_.tool_length_mm;
  compensation_.set_position(state_.position_mm);
  state_.tool_length_mm = length_mm;
  state_.tool_length_code = code.number;
  parameters_.set(parameter::tool_offset + 2, length_mm);
  return ok_status();
}

Status Executor::set_coordinate_system(const gcode::Block& b) {
  const gcode::Code& code = b.g[gcode::g_coordinates];
  if (!code.given()) return ok_status();
  if (compensation_.active())
    return gcode::error_at(where(), code.column,
                           "Cannot change coordinate systems with cutter radius comp on");
  static constexpr int kCodes[9] = {540, 550, 560, 570, 580, 590, 591, 592, 593};
  for (int i = 0; i < 9; ++i)
    if (code.is(kCodes[i])) parameters_.set(parameter::active_system, i + 1);
  reframe();
  return ok_status();
}

Status Executor::set_path_control(const gcode::Block& b) {
  const gcode::Code& control = b.g[gcode::g_path_control];
  if (!control.given()) return ok_status();
  state_.exact_stop = !control.is(640);
  state_.path_code = control.number;
  state_.path_tolerance_mm = -1.0;
  if (control.is(640) && b['P'].given()) {
    if (b['P'].value < 0.0) return gcode::error_at(where(), b['P'].column, "negative G64 tolerance P");
    if (b['P'].value > 0.0) state_.path_tolerance_mm = b['P'].value * state_.mm_per_unit();
  }
  return ok_status();
}

}  // namespace pkm::program::ngc
