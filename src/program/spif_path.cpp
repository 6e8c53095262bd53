#include "program/spif_path.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pkm::program {
namespace {

Status check_options(const SpifPathOptions& o) {
  auto bad = [](const std::string& what) { return make_error(ErrorCode::bad_input, what); };
  if (!o.profile.empty()) {
    if (!(o.step_down_mm > 0.0 && o.step_down_mm <= 1e3))
      return bad(fmt::format("step down {} mm: must be in (0, 1000]", o.step_down_mm));
    if (o.profile.back()[0] / o.step_down_mm > 100000.0)
      return bad(fmt::format("profile: {:g} mm deep in steps of {:g} mm is more than 100000 planes",
                             o.profile.back()[0], o.step_down_mm));
  } else if (!(o.radius_mm > 0.0 && o.radius_mm <= 1e5))
    return bad(fmt::format("radius {} mm: must be in (0, 1e5]", o.radius_mm));
  if (!(o.planes >= 1 && o.planes <= 100000))
    return bad(fmt::format("planes {}: must be 1 to 100000", o.planes));
  if (!(o.radius_step_mm >= 0.0) || !(o.radius_mm - (o.planes - 1) * o.radius_step_mm > 0.0)) {
    return bad(fmt::format("radius step {} mm: the last of {} circles from R {} mm would have no radius left",
                           o.radius_step_mm, o.planes, o.radius_mm));
  }
  if (!(o.step_down_mm > 0.0 && o.step_down_mm <= 1e3))
    return bad(fmt::format("step down {} mm: must be in (0, 1000]", o.step_down_mm));
  if (!(o.feed_mm_min > 0.0 && o.feed_mm_min <= 1e6))
    return bad(fmt::format("feed {} mm/min: must be in (0, 1e6]", o.feed_mm_min));
  if (!(o.approach_mm >= 0.0 && o.approach_mm <= 1e4))
    return bad(fmt::format("approach {} mm: must be in [0, 1e4]", o.approach_mm));
  if (!std::isfinite(o.z1_mm) || !o.centre_mm.allFinite() || std::abs(o.z1_mm) > 1e5 ||
      o.centre_mm.cwiseAbs().maxCoeff() > 1e5)
    return bad("z1 and the centre must be finite program coordinates within ±1e5 mm");
  return ok_status();
}

// Every circle's radius: the cone's, or the profile's at each step down (linear between its rows).
std::vector<double> circle_radii(const SpifPathOptions& o) {
  std::vector<double> radii;
  if (o.profile.empty()) {
    for (int n = 0; n < o.planes; ++n) radii.push_back(o.radius_mm - n * o.radius_step_mm);
    return radii;
  }
  std::size_t row = 0;
  for (int n = 0;; ++n) {
    const double depth = n * o.step_down_mm;
    if (depth > o.profile.back()[0] * (1.0 + 1e-12)) break;
    while (row + 2 < o.profile.size() && depth > o.profile[row + 1][0]) ++row;
    const auto& a = o.profile[row];
    const auto& b = o.profile[row + 1];
    const double w = std::min(1.0, (depth - a[0]) / (b[0] - a[0]));
    radii.push_back(a[1] + w * (b[1] - a[1]));
  }
  return radii;
}

}  // namespace

Result<std::string> spif_program_text(const SpifPathOptions& o) {
  if (Status s = check_options(o); !s) return s.error();
  const std::vector<double> radii = circle_radii(o);
  const double depth = o.depth_up ? o.step_down_mm : -o.step_down_mm;  // from plane to plane
  const char* arc = o.counter_clockwise ? "G3" : "G2";
  const double cx = o.centre_mm.x();
  const double cy = o.centre_mm.y();
  const std::string wall =
      o.profile.empty() ? fmt::format("R {:g} mm less {:g} mm per plane", o.radius_mm, o.radius_step_mm)
                        : fmt::format("R {:g} … {:g} mm along a profile of {} rows", radii.front(),
                                      radii.back(), o.profile.size());
  std::string text = fmt::format(
      "( pkm spif program: {} {}, {}, {:g} mm apart {}, first plane Z{:g} )\n"
      "( single point incremental forming, Smirnov 2019 3.8.1 )\n"
      "G21 G90 G17 G94\n",
      radii.size(), o.kind == SpifPathKind::helix ? "helical turns" : "planes", wall, o.step_down_mm,
      o.depth_up ? "up" : "down", o.z1_mm);
  // The approach comes from the sheet's near side: against the step direction.
  const double clear_z = o.z1_mm - (o.depth_up ? o.approach_mm : -o.approach_mm);
  text += fmt::format("G0 X{:.4f} Y{:.4f} Z{:.4f}\n", cx + radii.front(), cy, clear_z);
  text += fmt::format("G1 Z{:.4f} F{:g}\n", o.z1_mm, o.feed_mm_min);
  double z = o.z1_mm;
  for (std::size_t n = 0; n < radii.size(); ++n) {
    const double r = radii[n];
    if (n > 0) {
      // helix: only the radius steps (the turn went down); planes: down and in at once.
      if (o.kind == SpifPathKind::planes) z = o.z1_mm + static_cast<double>(n) * depth;
      text += fmt::format("G1 X{:.4f} Y{:.4f} Z{:.4f}\n", cx + r, cy, z);
    }
    if (o.kind == SpifPathKind::helix) {
      z = o.z1_mm + static_cast<double>(n + 1) * depth;
      text += fmt::format("{} X{:.4f} Y{:.4f} Z{:.4f} I{:.4f} J0\n", arc, cx + r, cy, z, -r);
    } else {
      text += fmt::format("{} X{:.4f} Y{:.4f} I{:.4f} J0\n", arc, cx + r, cy, -r);
    }
  }
  text += fmt::format("G0 Z{:.4f}\nM2\n", clear_z);
  return text;
}

}  // namespace pkm::program
