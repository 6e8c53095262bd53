#include "path/ellipsoid_cap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pkm::path {

Status validate_ellipsoid_cap(const EllipsoidCap& cap) {
  const Eigen::Vector3d& s = cap.semi_axes_mm;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(s[i]) || s[i] <= 0.0) {
      return make_error(
          ErrorCode::bad_input,
          fmt::format("ellipsoid semi-axis {} must be a positive length in mm, got {}", "abc"[i], s[i]));
    }
  }
  if (!cap.centre_mm.allFinite())
    return make_error(ErrorCode::bad_input, "ellipsoid centre must be three finite numbers (mm)");
  if (!std::isfinite(cap.depth_mm) || cap.depth_mm <= 0.0 || cap.depth_mm >= s.z()) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("cap depth must be > 0 and < the semi-axis c = {} mm (the cap ends above "
                                  "the equator, where the surface turns vertical), got {} mm",
                                  s.z(), cap.depth_mm));
  }
  return ok_status();
}

double cap_rim_sine(const EllipsoidCap& cap) {
  const double cosine = 1.0 - cap.depth_mm / cap.semi_axes_mm.z();
  return std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
}

Eigen::Vector2d cap_outline_semi_axes_mm(const EllipsoidCap& cap) {
  return cap.semi_axes_mm.head<2>() * cap_rim_sine(cap);
}

double cap_max_tilt_rad(const EllipsoidCap& cap) {
  // The normal is ∝ (x/a², y/b², z/c²); on the parallel of polar angle θ its horizontal part is largest on
  // the shorter axis, tan(tilt) = (c / min(a, b))·tan θ, which grows with θ: the rim holds the largest tilt.
  const double sine = cap_rim_sine(cap);
  const double cosine = 1.0 - cap.depth_mm / cap.semi_axes_mm.z();
  const double shorter = std::min(cap.semi_axes_mm.x(), cap.semi_axes_mm.y());
  return std::atan2(cap.semi_axes_mm.z() * sine, shorter * cosine);
}

Eigen::Vector3d cap_point_mm(const EllipsoidCap& cap, const Eigen::Vector2d& from_centre_mm) {
  const Eigen::Vector3d& s = cap.semi_axes_mm;
  const double u = from_centre_mm.x() / s.x(), v = from_centre_mm.y() / s.y();
  const double w = std::sqrt(std::max(0.0, 1.0 - u * u - v * v));
  return cap.centre_mm + Eigen::Vector3d(from_centre_mm.x(), from_centre_mm.y(), s.z() * w);
}

Eigen::Vector3d ellipsoid_normal(const EllipsoidCap& cap, const Eigen::Vector3d& point_mm) {
  const Eigen::Vector3d r = point_mm - cap.centre_mm;
  return r.cwiseQuotient(cap.semi_axes_mm.cwiseProduct(cap.semi_axes_mm)).normalized();
}

}  // namespace pkm::path
