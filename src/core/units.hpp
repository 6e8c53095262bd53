#pragma once
// Units inside pkm: mm, s, N, kg, rad. Files and the CLI use mm and degrees; conversion happens only here.
#include <numbers>

namespace pkm {

constexpr double kPi = std::numbers::pi;
constexpr double rad_from_deg(double angle_deg) {
  return angle_deg * (kPi / 180.0);
}
constexpr double deg_from_rad(double angle_rad) {
  return angle_rad * (180.0 / kPi);
}

}  // namespace pkm
