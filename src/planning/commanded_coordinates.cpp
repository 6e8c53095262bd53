#include "planning/commanded_coordinates.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/rotation.hpp"
#include "core/units.hpp"
#include "machine/mechanism_type.hpp"

namespace pkm::planning {

namespace {

using program::CanonicalMove;
using program::CanonicalProgram;
using program::MoveKind;

constexpr const char* kPositionNames[] = {"X", "Y", "Z"};
constexpr const char* kAbcNames[] = {"A", "B", "C"};

/// The name of coordinate k (0…5) of `mechanism`'s pose: X Y Z, then its angles (A B C in the abc
/// convention, "krylov angle 2" in another).
std::string coordinate_name(const Mechanism& mechanism, int k) {
  if (k < 3) return kPositionNames[k];
  if (mechanism.convention() == AngleConvention::abc) return kAbcNames[k - 3];
  return fmt::format("{} angle {}", to_string(mechanism.convention()), k - 2);
}

std::string controlled_names(const Mechanism& mechanism) {
  const AxisMask mask = mechanism.controlled_axes();
  std::string names;
  for (int k = 0; k < 6; ++k) {
    if (!mask.controlled[k]) continue;
    if (!names.empty()) names += ", ";
    names += coordinate_name(mechanism, k);
  }
  return names;
}

/// Angle between two angles in degrees, across the turn (359° and 1° are 2° apart).
double wrapped_difference_deg(double a_deg, double b_deg) {
  return std::abs(std::remainder(a_deg - b_deg, 360.0));
}

/// What moving an uncontrolled coordinate looks like: where, which, from and to.
struct UncontrolledMove {
  int line = 0;
  std::string coordinate;  ///< as the program names it ("X", "A", "the tool axis")
  std::string change;      ///< "from 0.0000 to 10.0000 mm"
};

Error uncontrolled_error(const Machine& machine, const CanonicalProgram& program, const UncontrolledMove& e) {
  const Mechanism& mechanism = *machine.mechanism;
  const std::string why =
      mechanism.is_planar()
          ? fmt::format("a planar mechanism ({}): it moves in its XY plane and controls {} only",
                        to_string(mechanism.type()), controlled_names(mechanism))
          : fmt::format("on a {} it follows from {}", to_string(mechanism.type()),
                        controlled_names(mechanism));
  return Error{ErrorCode::bad_input,
               fmt::format("{}:{}: {} is not a controlled coordinate of {} ({}); the program moves it {}",
                           program.source, e.line, e.coordinate, machine.name, why, e.change),
               ErrorLocation{program.source, e.line, 0, e.coordinate}};
}

/// The largest excursion of position coordinate c over an arc that starts at `start_mm`: the circle's extent
/// along c (an arc in the XY plane moves X and Y even where it ends where it began).
double arc_extent_mm(const CanonicalMove& move, const Eigen::Vector3d& start_mm, int c) {
  const Eigen::Vector3d from_centre = start_mm - move.center_mm;
  const Eigen::Vector3d radial = from_centre - move.normal * move.normal.dot(from_centre);
  const double n_c = std::min(1.0, std::abs(move.normal[c]));
  return radial.norm() * std::sqrt(1.0 - n_c * n_c);
}

/// The first position coordinate the move takes away from where the previous move left it.
std::optional<UncontrolledMove> moved_position(const AxisMask& mask, const CanonicalMove& move,
                                               const Eigen::Vector3d& previous_mm) {
  for (int c = 0; c < 3; ++c) {
    if (mask.controlled[c]) continue;
    if (std::abs(move.end_mm[c] - previous_mm[c]) > kUncontrolledChangeTolerance) {
      return UncontrolledMove{move.line, kPositionNames[c],
                              fmt::format("from {:.4f} to {:.4f} mm", previous_mm[c], move.end_mm[c])};
    }
    if (move.kind == MoveKind::arc && arc_extent_mm(move, previous_mm, c) > kUncontrolledChangeTolerance) {
      return UncontrolledMove{move.line, kPositionNames[c],
                              fmt::format("by ±{:.4f} mm along an arc", arc_extent_mm(move, previous_mm, c))};
    }
  }
  return std::nullopt;
}

/// The program's own orientation state between moves: its A B C, or its last tool axis.
struct ProgramOrientation {
  Eigen::Vector3d abc_deg = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> tool_axis;  ///< after a tool-axis move
};

/// A B C of the program that changed between `from` and `to`, as "A from 0.0000 to 4.0000 deg".
std::optional<UncontrolledMove> changed_abc(int line, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                            int only_index = -1) {
  for (int k = 0; k < 3; ++k) {
    if (only_index >= 0 && k != only_index) continue;
    if (std::abs(to[k] - from[k]) > kUncontrolledChangeTolerance)
      return UncontrolledMove{line, kAbcNames[k], fmt::format("from {:.4f} to {:.4f} deg", from[k], to[k])};
  }
  return std::nullopt;
}

/// The orientation a move asks for that the mechanism cannot set: with no controlled angle any change; with
/// two (a tripod's tilt) a change of the third, dependent one; on a planar machine a change of C where it has
/// no φ (A and B are refused by the path builder there).
std::optional<UncontrolledMove> moved_orientation(const Mechanism& mechanism, const CanonicalMove& move,
                                                  const ProgramOrientation& previous) {
  const AxisMask mask = mechanism.controlled_axes();
  const int controlled_angles =
      static_cast<int>(mask.controlled[3]) + mask.controlled[4] + mask.controlled[5];
  if (controlled_angles == 3) return std::nullopt;
  if (mechanism.is_planar()) {  // A and B are the path builder's; C is φ where the platform turns
    if (mask.controlled[5] || move.orientation != program::OrientationSource::abc) return std::nullopt;
    return changed_abc(move.line, previous.abc_deg, move.end_abc_deg, 2);
  }
  if (move.orientation == program::OrientationSource::tool_axis) {
    // The spin about the axis is free; a tilt of the axis needs two controlled angles.
    if (controlled_angles >= 2 || !previous.tool_axis) return std::nullopt;
    const double angle_deg = deg_from_rad(std::atan2(previous.tool_axis->cross(move.tool_axis).norm(),
                                                     previous.tool_axis->dot(move.tool_axis)));
    if (angle_deg <= kUncontrolledChangeTolerance) return std::nullopt;
    return UncontrolledMove{move.line, "the tool axis", fmt::format("by {:.4f} deg", angle_deg)};
  }
  if (controlled_angles == 0) return changed_abc(move.line, previous.abc_deg, move.end_abc_deg);
  int dependent = 3;
  while (mask.controlled[dependent]) ++dependent;
  if (mechanism.convention() == AngleConvention::abc)
    return changed_abc(move.line, previous.abc_deg, move.end_abc_deg, dependent - 3);
  // Another convention: the dependent angle of the machine's own convention, from the program's rotation.
  const auto own_angle_deg = [&](const Eigen::Vector3d& abc_deg) {
    const Eigen::Matrix3d r =
        rotation_from_angles(AngleConvention::abc, abc_deg * (std::numbers::pi / 180.0));
    return deg_from_rad(angles_from_rotation(mechanism.convention(), r)[dependent - 3]);
  };
  const double from_deg = own_angle_deg(previous.abc_deg), to_deg = own_angle_deg(move.end_abc_deg);
  if (wrapped_difference_deg(from_deg, to_deg) <= kUncontrolledChangeTolerance) return std::nullopt;
  return UncontrolledMove{move.line, coordinate_name(mechanism, dependent),
                          fmt::format("from {:.4f} to {:.4f} deg (A{:.4f} B{:.4f} C{:.4f})", from_deg, to_deg,
                                      move.end_abc_deg.x(), move.end_abc_deg.y(), move.end_abc_deg.z())};
}

}  // namespace

CommandedCoordinateCheck::CommandedCoordinateCheck(const Machine& machine, const CanonicalProgram& program)
    : machine_(machine),
      program_(program),
      all_controlled_(machine.mechanism->controlled_axes().count() == 6),
      position_mm_(program.start_mm),
      abc_deg_(program.start_abc_deg) {}

Status CommandedCoordinateCheck::add(const CanonicalMove& move) {
  if (all_controlled_) return ok_status();
  // A program of tool axes starts from (0,0,1), the axis CL data has before its first TLAXIS or 6-value GOTO:
  // a first move tilted away from it is a change of the tool axis like any later one.
  if (first_ && move.orientation == program::OrientationSource::tool_axis)
    tool_axis_ = Eigen::Vector3d::UnitZ();
  first_ = false;
  if (move.kind == MoveKind::dwell) return ok_status();
  const Mechanism& mechanism = *machine_.mechanism;
  if (auto moved = moved_position(mechanism.controlled_axes(), move, position_mm_))
    return uncontrolled_error(machine_, program_, *moved);
  if (auto turned = moved_orientation(mechanism, move, ProgramOrientation{abc_deg_, tool_axis_}))
    return uncontrolled_error(machine_, program_, *turned);
  position_mm_ = move.end_mm;
  if (move.orientation == program::OrientationSource::tool_axis) {
    tool_axis_ = move.tool_axis;
  } else {
    abc_deg_ = move.end_abc_deg;
    tool_axis_.reset();
  }
  return ok_status();
}

Status check_commanded_coordinates(const Machine& machine, const CanonicalProgram& program) {
  CommandedCoordinateCheck check(machine, program);
  for (const CanonicalMove& move : program.moves) {
    if (Status checked = check.add(move); !checked) return checked;
  }
  return ok_status();
}

}  // namespace pkm::planning
