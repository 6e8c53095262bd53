#include "redundancy/free_coordinates.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/units.hpp"

namespace pkm::redundancy {

std::optional<FreeSet> free_set_from_string(std::string_view name) {
  if (name == "spin") return FreeSet::spin;
  if (name == "all") return FreeSet::all;
  return std::nullopt;
}

std::string_view to_string(FreeSet set) {
  return set == FreeSet::spin ? "spin" : "all";
}

namespace {

constexpr double kDefaultHalfRangeDeg = 30.0;

// The tool axis in the platform frame: +Z of the program seen from the platform at home (path_builder).
Eigen::Vector3d home_tool_axis(const Mechanism& mechanism) {
  return mechanism.home().rotation.transpose() * Eigen::Vector3d::UnitZ();
}

}  // namespace

Result<FreeCoordinates::Kind> FreeCoordinates::kind_for(const Mechanism& mechanism, FreeSet set) {
  const AxisMask axes = mechanism.controlled_axes();
  // A planar mechanism that sets its turn φ (3-RPR) can leave φ free; a planar point (2-RPR) has no angle.
  if (mechanism.is_planar() && axes.controlled[5]) return Kind::planar_angle;
  const bool all_angles = axes.controlled[3] && axes.controlled[4] && axes.controlled[5];
  if (!all_angles) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("the {} controls no orientation that an operation could leave free; "
                                  "redundancy laws need a planar 3-DOF or a six-axis machine",
                                  to_string(mechanism.type())));
  }
  return set == FreeSet::spin ? Kind::spin : Kind::convention_angles;
}

FreeValues FreeCoordinates::values_for(Kind kind, AngleConvention convention,
                                       const Eigen::Vector3d& tool_axis_platform,
                                       const Eigen::Matrix3d& rotation, const PathPoint& point) {
  FreeValues values = FreeValues::Zero();
  switch (kind) {
    case Kind::planar_angle:
      values[0] = std::atan2(rotation(1, 0), rotation(0, 0));
      break;
    case Kind::spin: {
      // R = R_axis · Rot(a', s) ⇒ Rot(a', s) = R_axisᵀ R; its angle about a' is s.
      const Eigen::Matrix3d turn = point.axis_rotation.transpose() * rotation;
      const Eigen::AngleAxisd angle_axis(turn);
      const double sign = angle_axis.axis().dot(tool_axis_platform) >= 0.0 ? 1.0 : -1.0;
      values[0] = std::remainder(sign * angle_axis.angle(), 2.0 * kPi);
      break;
    }
    case Kind::convention_angles:
      values = angles_from_rotation(convention, rotation);
      break;
  }
  return values;
}

Result<FreeCoordinates> FreeCoordinates::create(const Mechanism& mechanism, FreeSet set,
                                                const FreeBounds& bounds_deg, const FreeValues& start_rad) {
  auto kind = kind_for(mechanism, set);
  if (!kind) return kind.error();
  FreeCoordinates free;
  free.kind_ = *kind;
  free.count_ = *kind == Kind::convention_angles ? 3 : 1;
  free.convention_ = mechanism.convention();
  free.tool_axis_platform_ = home_tool_axis(mechanism);
  free.start_ = start_rad;
  const int ranges = static_cast<int>(bounds_deg.size());
  if (ranges > 1 && ranges != free.count_) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("bounds: {} ranges given; give one for every free coordinate or one for each "
                    "of the {} ({})",
                    ranges, free.count_, free.count_ == 3 ? "three angles" : free.name(0)));
  }
  for (int i = 0; i < free.count_; ++i) {
    if (ranges == 0) {
      free.lower_rad_[i] = start_rad[i] - rad_from_deg(kDefaultHalfRangeDeg);
      free.upper_rad_[i] = start_rad[i] + rad_from_deg(kDefaultHalfRangeDeg);
      continue;
    }
    const std::array<double, 2>& range = bounds_deg[ranges == 1 ? 0 : i];
    if (!(range[0] < range[1])) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("bounds {},{}: the lower bound must be below the upper one (degrees)",
                                    range[0], range[1]));
    }
    free.lower_rad_[i] = rad_from_deg(range[0]);
    free.upper_rad_[i] = rad_from_deg(range[1]);
    if (start_rad[i] < free.lower_rad_[i] - 1e-9 || start_rad[i] > free.upper_rad_[i] + 1e-9) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("the program starts with {} = {:.4f} deg, outside the bounds {},{}",
                                    free.name(i), deg_from_rad(start_rad[i]), range[0], range[1]));
    }
  }
  return free;
}

std::string FreeCoordinates::name(int i) const {
  switch (kind_) {
    case Kind::planar_angle:
      return "phi";
    case Kind::spin:
      return "spin";
    case Kind::convention_angles:
      break;
  }
  static constexpr std::array<std::array<const char*, 3>, 3> kNames{
      {{"A", "B", "C"}, {"psi", "theta", "gamma"}, {"psi", "nutation", "phi"}}};
  const int convention = convention_ == AngleConvention::abc      ? 0
                         : convention_ == AngleConvention::krylov ? 1
                                                                  : 2;
  return kNames[convention][i];
}

FreeValues FreeCoordinates::clamp(const FreeValues& values) const {
  FreeValues clamped = values;
  for (int i = 0; i < count_; ++i) clamped[i] = std::clamp(values[i], lower_rad_[i], upper_rad_[i]);
  return clamped;
}

Pose FreeCoordinates::pose(const PathPoint& point, const FreeValues& values) const noexcept {
  Pose pose;
  pose.position_mm = point.position_mm;
  switch (kind_) {
    case Kind::planar_angle:
      pose.rotation = rot_z(values[0]);
      break;
    case Kind::spin:
      pose.rotation =
          point.axis_rotation * Eigen::AngleAxisd(values[0], tool_axis_platform_).toRotationMatrix();
      break;
    case Kind::convention_angles:
      pose.rotation = rotation_from_angles(convention_, values);
      break;
  }
  return pose;
}

FreeValues FreeCoordinates::values_of(const Eigen::Matrix3d& rotation, const PathPoint& point) const {
  return values_for(kind_, convention_, tool_axis_platform_, rotation, point);
}

}  // namespace pkm::redundancy
