#pragma once
// The arc of an APT `CIRCLE/xc,yc,zc,i,j,k,r` record and the GOTO that follows it.
//
// Direction: APT (and NX, Catia, Mastercam when they write CIRCLE records) states the direction of travel by
// the sign of the axis: the tool moves counter-clockwise about (i,j,k), from the current point to the GOTO's
// point. A clockwise (G2-like) arc in the XY plane is therefore written with axis (0,0,-1). We follow that
// rule exactly: the canonical arc gets normal = (i,j,k) normalised, and the sweep is the counter-clockwise
// angle about it from the start to the end, in (0°, 360°] (a GOTO back to the start point is a full circle).
// If the end differs from the start along the axis, the move is a helix.
#include <Eigen/Core>
#include <string>

#include "program/canonical_program.hpp"

namespace pkm::program {

struct ClCircle {
  Eigen::Vector3d center_mm = Eigen::Vector3d::Zero();  ///< any point on the axis
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();      ///< unit; travel is counter-clockwise about it
  double radius_mm = 0.0;  ///< 0: not stated (a six-value CIRCLE): the start point's distance from the axis
  int turns = 1;           ///< TIMES,n: a helix of n turns (n − 1 full turns before the end point)
};

/// The largest difference between the stated radius and the start's or end's distance from the axis that is
/// taken for rounding in the CL file: 0.005 mm, or 0.1 % of the radius for large arcs.
double cl_arc_radius_tolerance(double radius_mm);

/// G17/G18/G19 name the plane by its normal; an oblique CL arc gets the one its axis is closest to.
Plane cl_nearest_plane(const Eigen::Vector3d& axis);

/// Turns `move` (whose end_mm is set) into the arc of `circle` starting at `start_mm`: kind, center_mm (moved
/// along the axis to the start's height), normal, plane (the principal plane nearest to the arc's), turns.
/// Returns an empty string, or why the points do not lie on the circle.
/// Unit tangent of an arc move (counter-clockwise about its normal) where it leaves `start_mm`, and where it
/// arrives at its end; the helix's rise is left out (the checks that use them compare directions in the arc's
/// plane).
Eigen::Vector3d cl_arc_start_tangent(const CanonicalMove& arc, const Eigen::Vector3d& start_mm);
Eigen::Vector3d cl_arc_end_tangent(const CanonicalMove& arc);
/// The angle the arc sweeps from `start_mm` to its end, in (0, 2π] (a return to the start is a full turn),
/// counter-clockwise about its normal; further TIMES turns not counted.
double cl_arc_sweep_rad(const CanonicalMove& arc, const Eigen::Vector3d& start_mm);

std::string make_cl_arc(const ClCircle& circle, const Eigen::Vector3d& start_mm, CanonicalMove& move);

}  // namespace pkm::program
