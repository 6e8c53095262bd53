#include "program/spif_path.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm::program {
namespace {

Status check_options(const SpifPathOptions& o) {
  auto bad = [](const std::string& what) { return make_error(ErrorCode::bad_input, what); };
  if (!(o.radius_mm > 0.0 && o.radius_mm <= 1e5))
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

}  // namespace

Result<std::string> spif_program_text(const SpifPathOptions& o) {
  if (Status s = check_options(o); !s) return s.error();
  const double depth = o.depth_up ? o.step_down_mm : -o.step_down_mm;  // from plane to plane
  const char* arc = o.counter_clockwise ? "G3" : "G2";
  const double cx = o.centre_mm.x();
  const double cy = o.centre_mm.y();
  std::string text = fmt::format(
      "( pkm spif program: {} {}, R {:g} mm less {:g} mm per plane, {:g} mm apart {}, first plane Z{:g} )\n"
      "( single point incremental forming, Smirnov 2019 3.8.1: the seeds' cone by default )\n"
      "G21 G90 G17 G94\n",
      o.planes, o.kind == SpifPathKind::helix ? "helical turns" : "planes", o.radius_mm, o.radius_step_mm,
      o.step_down_mm, o.depth_up ? "up" : "down", o.z1_mm);
  // The approach comes from the sheet's near side: against the step direction.
  const double clear_z = o.z1_mm - (o.depth_up ? o.approach_mm : -o.approach_mm);
  text += fmt::format("G0 X{:.4f} Y{:.4f} Z{:.4f}\n", cx + o.radius_mm, cy, clear_z);
  text += fmt::format("G1 Z{:.4f} F{:g}\n", o.z1_mm, o.feed_mm_min);
  double z = o.z1_mm;
  for (int n = 0; n < o.planes; ++n) {
    const double r = o.radius_mm - n * o.radius_step_mm;
    if (n > 0) {
      // helix: only the radius steps (the turn went down); planes: down and in at once.
      if (o.kind == SpifPathKind::planes) z = o.z1_mm + n * depth;
      text += fmt::format("G1 X{:.4f} Y{:.4f} Z{:.4f}\n", cx + r, cy, z);
    }
    if (o.kind == SpifPathKind::helix) {
      z = o.z1_mm + (n + 1) * depth;
      text += fmt::format("{} X{:.4f} Y{:.4f} Z{:.4f} I{:.4f} J0\n", arc, cx + r, cy, z, -r);
    } else {
      text += fmt::format("{} X{:.4f} Y{:.4f} I{:.4f} J0\n", arc, cx + r, cy, -r);
    }
  }
  text += fmt::format("G0 Z{:.4f}\nM2\n", clear_z);
  return text;
}

}  // namespace pkm::program
