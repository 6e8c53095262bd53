#include "io/pose_input.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "core/units.hpp"

namespace pkm {

namespace {

constexpr double kMaxUserNumber = 1e6;  // mm or degrees

}  // namespace

Result<std::vector<double>> parse_number_list(std::string_view text, std::string_view field) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    std::string token(
        text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    const auto first = token.find_first_not_of(" \t");
    const auto last = token.find_last_not_of(" \t");
    token = first == std::string::npos ? "" : token.substr(first, last - first + 1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    // 1e999 is a number, only not one a double holds: say so rather than "not a number".
    if (!token.empty() && ec == std::errc::result_out_of_range && end == token.data() + token.size()) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}: '{}' is out of range (at most {:g} in size; item {} of '{}')", field,
                                    token, kMaxUserNumber, out.size() + 1, text));
    }
    if (token.empty() || ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) {
      return make_error(ErrorCode::bad_input, fmt::format("{}: '{}' is not a number (item {} of '{}')", field,
                                                          token, out.size() + 1, text));
    }
    // No machine reaches a kilometre or turns a million degrees: such a number is a typo, and 1e308 would
    // overflow to infinity inside the kinematics.
    if (std::abs(value) > kMaxUserNumber) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}: '{}' is out of range (at most {:g} in size; item {} of '{}')", field,
                                    token, kMaxUserNumber, out.size() + 1, text));
    }
    out.push_back(value);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

Result<Pose> pose_from_user(const Mechanism& mechanism, const std::vector<double>& values,
                            std::string_view field) {
  PoseVector c = PoseVector::Zero();
  const AxisMask mask = mechanism.controlled_axes();
  const auto names = controlled_coordinate_names(mechanism);
  // A planar pose is its controlled coordinates only (x, y and, where controlled, φ); a spatial one is all
  // six, or the controlled ones of a reduced-DOF mechanism.
  const bool controlled_only = static_cast<int>(values.size()) == mask.count();
  if (mechanism.is_planar() && !controlled_only) {
    return make_error(ErrorCode::bad_input, fmt::format("{}: a {} pose is {} numbers ({}), got {}", field,
                                                        to_string(mechanism.type()), mask.count(),
                                                        fmt::join(names, ","), values.size()));
  }
  if (values.size() == 6 && !mechanism.is_planar()) {
    for (int i = 0; i < 6; ++i) c[i] = i < 3 ? values[i] : rad_from_deg(values[i]);
  } else if (controlled_only) {
    int k = 0;
    for (int i = 0; i < 6; ++i) {
      if (mask.controlled[i]) c[i] = i < 3 ? values[k++] : rad_from_deg(values[k++]);
    }
  } else {
    return make_error(
        ErrorCode::bad_input,
        fmt::format(
            "{}: expected 6 numbers x,y,z (mm) and 3 angles (deg, {} convention){}, got {}", field,
            to_string(mechanism.convention()),
            mask.count() < 6 ? fmt::format(", or the controlled {}", fmt::join(names, ",")) : std::string(),
            values.size()));
  }
  return mechanism.complete_pose(pose_from_vector(mechanism.convention(), c));
}

std::vector<double> user_from_pose(const Mechanism& mechanism, const Pose& pose) {
  // "+ 0.0" turns a negative zero into zero, so users never see "-0.00".
  const PoseVector c = vector_from_pose(mechanism.convention(), pose).array() + 0.0;
  std::vector<double> out;
  const AxisMask mask = mechanism.controlled_axes();
  for (int i = 0; i < 6; ++i) {
    // Planar mechanisms show their controlled coordinates only; spatial ones the whole pose.
    if (mechanism.is_planar() && !mask.controlled[i]) continue;
    out.push_back(i < 3 ? c[i] : deg_from_rad(c[i]));
  }
  return out;
}

Result<ActuatorVector> actuators_from_user(const Mechanism& mechanism, const std::vector<double>& values,
                                           std::string_view field) {
  const int n = mechanism.actuator_count();
  if (static_cast<int>(values.size()) != n) {
    return make_error(ErrorCode::bad_input, fmt::format("{}: a {} has {} actuators, got {} numbers", field,
                                                        to_string(mechanism.type()), n, values.size()));
  }
  ActuatorVector q(n);
  for (int j = 0; j < n; ++j) q[j] = mechanism.actuators_are_angles() ? rad_from_deg(values[j]) : values[j];
  return q;
}

std::vector<double> user_from_actuators(const Mechanism& mechanism, const ActuatorVector& actuators) {
  std::vector<double> out;
  for (int j = 0; j < actuators.size(); ++j) {
    out.push_back(mechanism.actuators_are_angles() ? deg_from_rad(actuators[j]) : actuators[j]);
  }
  return out;
}

const char* actuator_unit_name(const Mechanism& mechanism) {
  return mechanism.actuators_are_angles() ? "deg" : "mm";
}

}  // namespace pkm
