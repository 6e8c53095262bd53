#pragma once
// Arc geometry of G2/G3: the centre from I J K (incremental or absolute) or from R, checked the way
// LinuxCNC's rs274 checks it (tolerances measured with rs274; docs/part-programs.md), and the swept angle.
// Everything here is in mm, in the arc plane's (first, second) frame as rs274 prints it: (X, Y) for G17,
// (Z, X) for G18, (Y, Z) for G19.
#include <Eigen/Core>
#include <string>

#include "program/canonical_program.hpp"

namespace pkm::program::gcode {

/// Indices of the plane's first and second axes and of its normal axis into (x, y, z).
struct PlaneAxes {
  int first;
  int second;
  int normal;
};
PlaneAxes axes_of(Plane plane);

/// Unit normal of the plane's (first, second) frame: first × second (+Z, +Y, +X).
Eigen::Vector3d plane_normal(Plane plane);

/// Tolerances, mm. LinuxCNC (measured with rs274): an I J K arc is rejected when its end radius differs from
/// its start radius by more than both 0.02·√2 mm in G21 (0.002·√2 inch in G20) and 0.1 % of the larger
/// radius; an R arc whose chord is longer than 2|R| is accepted as a half circle up to 0.00005 inch (0.00127
/// mm).
struct ArcTolerances {
  double radius_abs_mm;
  double radius_rel = 0.001;
  double r_word_mm = 0.00127;
};
ArcTolerances arc_tolerances(bool inch);

/// The failure of an arc computation; the caller adds line and column.
struct ArcProblem {
  std::string message;
};

/// Centre from a centre point already in program coordinates (I J K resolved): checks zero radius and that
/// the end lies on the circle. Returns an empty message when the arc is fine.
ArcProblem check_centre_arc(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                            const Eigen::Vector3d& centre, Plane plane, const ArcTolerances& tolerances);

/// Centre of an R arc (R < 0: the arc longer than a half circle). On failure the message is set.
ArcProblem centre_from_radius(const Eigen::Vector3d& start, const Eigen::Vector3d& end, double radius_mm,
                              bool clockwise, Plane plane, const ArcTolerances& tolerances,
                              Eigen::Vector3d& centre);

/// Angle swept by an arc move (rad, > 0), full turns included; `start` is the previous move's end. An end at
/// the start's angle is a full circle.
double arc_sweep_rad(const Eigen::Vector3d& start, const CanonicalMove& arc);

/// Length of the helix (mm): the arc at the start radius combined with the travel along the normal.
double arc_length_mm(const Eigen::Vector3d& start, const CanonicalMove& arc);

}  // namespace pkm::program::gcode
