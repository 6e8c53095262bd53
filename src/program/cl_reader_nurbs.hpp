#pragma once
// NX NURBS records of CL data: the curve being collected. See cl_reader_nurbs.cpp.
#include <Eigen/Core>
#include <vector>

#include "program/cl_reader_state.hpp"

namespace pkm::program {

struct ClNurbsState {
  bool collecting = false;
  ClPosition at;                            ///< the NURBS statement: its line goes on every move of the curve
  Eigen::Vector3d start_mm;                 ///< the point before NURBS: the first control point
  std::vector<double> knots;                ///< as listed (without the clamped start; the last is 1)
  std::vector<Eigen::Vector3d> control_mm;  ///< the CNTRL points, mm
  ClPosition first_cntrl_at;
};

/// A clamped cubic B-spline (order 4): control points P0…Pn and the full knot vector (n + 5 knots).
struct ClCubicSpline {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> knots;
  /// The point at parameter t in [knots[3], knots[n+1]].
  Eigen::Vector3d at(double t) const;
};

/// Parameters t0 = start < t1 < … < tk = end such that the chord between successive points of the curve
/// stays within `tolerance_mm` of it (a bound, not a sample), knot values among them.
std::vector<double> cl_spline_chord_parameters(const ClCubicSpline& spline, double tolerance_mm);

}  // namespace pkm::program
