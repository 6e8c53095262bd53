// The executor's non-modal codes that set offsets and stored positions: G10 (work offsets and tool data),
// G28/G30 (go home through a point) and G28.1/G30.1 (store home), G92/G92.1/G92.2/G92.3 and G52.
// LinuxCNC keeps all of them in its parameters (ngc_work_offsets.hpp); the frame is re-read afterwards.
#include <fmt/format.h>

#include <cmath>

#include "program/ngc_executor.hpp"
#include "program/ngc_executor_support.hpp"
#include "program/ngc_work_offsets.hpp"

namespace pkm::program::ngc {

using namespace executor_support;

namespace {

constexpr char kAxes[6] = {'X', 'Y', 'Z', 'A', 'B', 'C'};

bool any_axis(const gcode::Block& b) {
  return b.first_axis_column() > 0;
}

}  // namespace

Status Executor::non_modal(const gcode::Block& b) {
  const gcode::Code& code = b.g[gcode::g_non_modal];
  if (!code.given() || code.is(40) || code.is(530)) return ok_status();
  const bool changes_offsets = code.is(100) || code.is(520) || code.number / 10 == 92;
  if (changes_offsets && compensation_.active())
    return gcode::error_at(where(), code.column,
                           "Cannot change coordinate systems with cutter radius comp on");
  if (code.is(100)) return set_g10(b);
  if ((code.is(280) || code.is(300)) && compensation_.active())
    return gcode::error_at(where(), code.column, "Cannot use G28 or G30 with cutter radius comp");
  if (code.is(280) || code.is(300)) return return_home(b, code.number);
  if (code.is(281) || code.is(301)) {
    store_home(code.number);
    return ok_status();
  }
  return set_axis_offsets(b, code.number);
}

Status Executor::set_g10(const gcode::Block& b) {
  const gcode::Code& code = b.g[gcode::g_non_modal];
  if (!b['L'].given())
    return gcode::error_at(where(), code.column, "G10 needs an L word (L1, L2, L10, L11 or L20)");
  const int l = whole(b['L'].value);
  if (!b['P'].given()) return gcode::error_at(where(), code.column, fmt::format("G10 L{} needs a P word", l));
  if (l == 1 || l == 10 || l == 11) return set_g10_tool(b, l);
  if (l == 2 || l == 20) return set_g10_offsets(b, l);
  return gcode::error_at(where(), b['L'].column, fmt::format("G10 L{}: L must be 1, 2, 10, 11 or 20", l));
}

Status Executor::set_g10_tool(const gcode::Block& b, int l) {
  const int tool = whole(b['P'].value);
  if (tool <= 0) return gcode::error_at(where(), b['P'].column, "G10 tool data needs a tool number P ≥ 1");
  if (!tools_) tools_.emplace();
  ToolEntry entry;
  if (const ToolEntry* old = tools_->find(tool)) entry = *old;
  entry.tool = tool;
  if (entry.pocket == 0) entry.pocket = tool;
  const double unit = state_.mm_per_unit();
  if (b['R'].given()) entry.diameter_mm = 2.0 * b['R'].value * unit;
  if (b['Z'].given()) {
    const double z_mm = b['Z'].value * unit;
    if (l == 1) {
      entry.length_mm = z_mm;
    } else {
      // L10: the length that makes the current point read Z (G43 in effect); L11: likewise in G59.3 without
      // G92. The controlled point (work Z + tool length in effect) does not move.
      const double machine_z_mm = machine_mm(state_.position_mm).z();
      if (l == 10) {
        entry.length_mm = state_.tool_length_mm + state_.position_mm.z() - z_mm;
      } else {
        entry.length_mm = machine_z_mm - parameters_.get(parameter::system_base(9) + 2) - z_mm;
      }
    }
  }
  tools_->set(entry);
  if (tool == state_.current_tool) {
    state_.spindle_tool_length_mm = entry.length_mm;
    state_.spindle_tool_diameter_mm = entry.diameter_mm;
  }
  return ok_status();
}

Status Executor::set_g10_offsets(const gcode::Block& b, int l) {
  int system = whole(b['P'].value);
  if (system < 0 || system > 9)
    return gcode::error_at(where(), b['P'].column, "G10 L2/L20 P must be 0 (the active system) to 9");
  if (system == 0) system = active_system_of(parameters_);
  const int base = parameter::system_base(system);
  const double unit = state_.mm_per_unit();
  if (l == 2) {
    for (int i = 0; i < 6; ++i)
      if (b[kAxes[i]].given()) parameters_.set(base + i, b[kAxes[i]].value * (i < 3 ? unit : 1.0));
    if (b['R'].given()) parameters_.set(base + 9, b['R'].value);
  } else {
    // L20: the offsets that make the current point have the given coordinates in system P.
    if (b['R'].given()) parameters_.set(base + 9, b['R'].value);
    const Eigen::Vector3d work_mm = to_work_mm(state_.frame, state_.position_mm);
    const Eigen::Vector3d work_abc = state_.abc_deg + state_.frame.g5x_abc_deg + state_.frame.g92_abc_deg;
    WorkFrame target = read_work_frame(parameters_);
    const int active = active_system_of(parameters_);
    if (system != active) {
      // read_work_frame reads the active system; the target's own offsets and rotation are wanted here.
      for (int i = 0; i < 3; ++i) target.g5x_mm[i] = parameters_.get(base + i);
      target.xy_rotation_deg = parameters_.get(base + 9);
    }
    Eigen::Vector3d wanted = to_program_mm(target, work_mm);
    for (int i = 0; i < 3; ++i)
      if (b[kAxes[i]].given()) wanted[i] = b[kAxes[i]].value * unit;
    target.g5x_mm.setZero();
    const Eigen::Vector3d g5x_mm = work_mm - to_work_mm(target, wanted);
    for (int i = 0; i < 3; ++i)
      if (b[kAxes[i]].given()) parameters_.set(base + i, g5x_mm[i]);
    for (int i = 0; i < 3; ++i)
      if (b[kAxes[i + 3]].given())
        parameters_.set(base + 3 + i, work_abc[i] - target.g92_abc_deg[i] - b[kAxes[i + 3]].value);
  }
  reframe();
  return ok_status();
}

// G92 makes the current point have the given coordinates; G52 sets the same offset to the given values;
// G92.1 clears it (and its parameters), G92.2 suspends it, G92.3 applies the stored one again.
Status Executor::set_axis_offsets(const gcode::Block& b, int code) {
  const double unit = state_.mm_per_unit();
  if (code == 920 || code == 520) {
    if (!any_axis(b))
      return gcode::error_at(where(), b.g[gcode::g_non_modal].column,
                             fmt::format("{} needs at least one axis word", gcode::code_name('G', code)));
    const bool applied = parameters_.get(parameter::g92_applied) != 0.0;
    for (int i = 0; i < 6; ++i) {
      // mm for X Y Z, degrees for A B C.
      const double old_value = applied ? parameters_.get(parameter::g92 + i) : 0.0;
      double value = old_value;
      if (b[kAxes[i]].given()) {
        const double word = b[kAxes[i]].value * (i < 3 ? unit : 1.0);
        const double current = i < 3 ? state_.position_mm[i] : state_.abc_deg[i - 3];
        value = code == 520 ? word : current + old_value - word;
      }
      parameters_.set(parameter::g92 + i, value);
    }
    parameters_.set(parameter::g92_applied, 1.0);
  } else if (code == 921) {
    for (int i = 0; i < 9; ++i) parameters_.set(parameter::g92 + i, 0.0);
    parameters_.set(parameter::g92_applied, 0.0);
  } else if (code == 922) {
    parameters_.set(parameter::g92_applied, 0.0);
  } else if (code == 923) {
    parameters_.set(parameter::g92_applied, 1.0);
  }
  reframe();
  return ok_status();
}

// G28/G30: a rapid to the intermediate point the axis words give (rs274 emits it even when there are none),
// then a rapid to the stored position of the named axes (all axes when none is named).
Status Executor::return_home(const gcode::Block& b, int code) {
  const int stored = code == 280 ? parameter::g28 : parameter::g30;
  Eigen::Vector3d abc = state_.abc_deg;
  Eigen::Vector3d through = state_.position_mm;
  if (auto target = target_of(b, through, abc); !target) return target;
  CanonicalMove m = new_move(MoveKind::rapid);
  m.end_mm = through;
  m.end_abc_deg = abc;
  if (auto emitted = emit(m); !emitted) return emitted;
  state_.position_mm = through;
  state_.abc_deg = abc;
  const bool all = !any_axis(b);
  Eigen::Vector3d machine = machine_mm(state_.position_mm);
  for (int i = 0; i < 3; ++i)
    if (all || b[kAxes[i]].given()) machine[i] = parameters_.get(stored + i);
  Eigen::Vector3d home = program_from_machine_mm(machine);
  for (int i = 0; i < 3; ++i)
    if (!(all || b[kAxes[i]].given())) home[i] = state_.position_mm[i];
  for (int i = 0; i < 3; ++i)
    if (all || b[kAxes[i + 3]].given())
      abc[i] = parameters_.get(stored + 3 + i) - state_.frame.g5x_abc_deg[i] - state_.frame.g92_abc_deg[i];
  m = new_move(MoveKind::rapid);
  m.end_mm = home;
  m.end_abc_deg = abc;
  if (auto emitted = emit(m); !emitted) return emitted;
  state_.position_mm = home;
  state_.abc_deg = abc;
  return ok_status();
}

void Executor::store_home(int code) {
  const int stored = code == 281 ? parameter::g28 : parameter::g30;
  const Eigen::Vector3d machine = machine_mm(state_.position_mm);
  for (int i = 0; i < 3; ++i) {
    parameters_.set(stored + i, machine[i]);
    parameters_.set(stored + 3 + i,
                    state_.abc_deg[i] + state_.frame.g5x_abc_deg[i] + state_.frame.g92_abc_deg[i]);
  }
}

// LinuxCNC's machine coordinates: the work point plus the tool length offset along Z.
Eigen::Vector3d Executor::machine_mm(const Eigen::Vector3d& program_mm) const {
  Eigen::Vector3d m = to_work_mm(state_.frame, program_mm);
  m.z() += state_.tool_length_mm;
  return m;
}

Eigen::Vector3d Executor::program_from_machine_mm(const Eigen::Vector3d& machine) const {
  Eigen::Vector3d work = machine;
  work.z() -= state_.tool_length_mm;
  return to_program_mm(state_.frame, work);
}

}  // namespace pkm::program::ngc
