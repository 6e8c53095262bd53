#pragma once
// The surface the machining strategies are compared on (Rusanov et al., Fig. 9): the top of
// an ellipsoid with semi-axes a, b, c along x, y, z, cut off by a horizontal plane `depth_mm` below its top.
// The cut is a plane of constant height, so the cap's outline seen from above is an ellipse with semi-axes
// a·sin θ, b·sin θ (cos θ = 1 − depth/c), the parallels are smaller ellipses like it, and every point of the
// cap is the graph z(x, y) of its projection: the strategies are drawn in the xy plane and lifted onto the
// surface. Program coordinates, mm.
#include <Eigen/Core>

#include "core/result.hpp"

namespace pkm::path {

struct EllipsoidCap {
  Eigen::Vector3d semi_axes_mm{100.0, 80.0, 40.0};  ///< a, b, c along x, y, z
  Eigen::Vector3d centre_mm{0.0, 0.0, -40.0};       ///< the ellipsoid's centre
  double depth_mm = 4.0;  ///< the cap: z ≥ top − depth, 0 < depth < c (above the equator)
};

/// Refuses non-finite or non-positive semi-axes, a non-finite centre, and a depth outside (0, c): at the
/// equator the surface turns vertical and the tool axis horizontal.
Status validate_ellipsoid_cap(const EllipsoidCap& cap);

/// sin θ of the cap's rim (θ the polar angle of the ellipsoid's parametrisation).
double cap_rim_sine(const EllipsoidCap& cap);
/// The semi-axes of the cap's outline seen from above (x, y), mm.
Eigen::Vector2d cap_outline_semi_axes_mm(const EllipsoidCap& cap);
/// The largest angle between the surface normal and +z on the cap (at the rim, on the shorter axis), rad.
double cap_max_tilt_rad(const EllipsoidCap& cap);

/// The surface point above (x, y) measured from the centre, which must lie inside the outline (to rounding).
Eigen::Vector3d cap_point_mm(const EllipsoidCap& cap, const Eigen::Vector2d& from_centre_mm);
/// The unit outward normal of the ellipsoid at a surface point.
Eigen::Vector3d ellipsoid_normal(const EllipsoidCap& cap, const Eigen::Vector3d& point_mm);

}  // namespace pkm::path
