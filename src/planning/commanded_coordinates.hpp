#pragma once
// A program may only move the coordinates its machine controls. A 3-RPS tripod sets Z, A and B; its X, Y and
// C follow from them. A tricept sets X, Y and Z; its orientation follows. A planar machine moves in its XY
// plane. A program that moves a coordinate the machine does not control describes a motion the machine
// cannot make: planned anyway, the plan would report the coordinates it could follow and silently drop the
// others (a 78 mm XY pocket "planned" on a tripod whose platform only moves in Z). Such a program is refused
// at the first line that moves such a coordinate.
//
// "Moves" compares each move's end with the previous one (the program's start for the first), so a program
// that restates an uncontrolled coordinate without changing it (the usual "G0 X0 Y0 Z5" of a post) is fine.
// An arc moves both coordinates of its plane. Orientation given by a tool axis (CL data) is compared axis to
// axis, leaving the spin about the axis free, as the CL data does.
#include <Eigen/Core>
#include <optional>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "program/canonical_program.hpp"

namespace pkm::planning {

/// Smallest change of an uncontrolled coordinate that counts as moving it: what a four-decimal program
/// states (mm, or degrees for angles and for the angle between two tool axes).
inline constexpr double kUncontrolledChangeTolerance = 1e-4;

/// The same check move by move, as a program is read (the moves in order, dwells included).
class CommandedCoordinateCheck {
 public:
  CommandedCoordinateCheck(const Machine& machine, const program::CanonicalProgram& program);
  Status add(const program::CanonicalMove& move);

 private:
  const Machine& machine_;
  const program::CanonicalProgram& program_;
  bool all_controlled_ = false;
  bool first_ = true;
  Eigen::Vector3d position_mm_;
  Eigen::Vector3d abc_deg_;
  std::optional<Eigen::Vector3d> tool_axis_;
};

/// Ok, or ErrorCode::bad_input at the first move (program file and line) that moves a coordinate `machine`
/// does not control, naming the coordinate, the ones it follows from, and the values.
Status check_commanded_coordinates(const Machine& machine, const program::CanonicalProgram& program);

}  // namespace pkm::planning
