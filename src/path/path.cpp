#include "path/path.hpp"

#include <algorithm>

namespace pkm::path {

int Path::find_segment(double s, int hint) const {
  const int n = static_cast<int>(segments.size());
  if (n == 0) return 0;
  int i = std::clamp(hint, 0, n - 1);
  if (s < segments[i].s_start) {  // went backwards: binary search
    auto it = std::upper_bound(segments.begin(), segments.end(), s,
                               [](double value, const Segment& seg) { return value < seg.s_start; });
    return std::max(0, static_cast<int>(it - segments.begin()) - 1);
  }
  while (i + 1 < n && s >= segments[i + 1].s_start) ++i;
  return i;
}

static double blend_parameter(const BlendTable& table, double fraction) {
  // The knot piece holding the fraction (knots are increasing in s), then cubic Hermite within it.
  constexpr int last = kBlendKnots - 1;
  const double x = std::clamp(fraction, 0.0, 1.0);
  const int k = std::clamp(
      static_cast<int>(std::upper_bound(table.s.begin() + 1, table.s.end() - 1, x) - table.s.begin()) - 1, 0,
      last - 1);
  const double h = table.s[k + 1] - table.s[k];
  if (!(h > 0.0)) return static_cast<double>(k) / last;
  const double t = std::clamp((x - table.s[k]) / h, 0.0, 1.0);
  const double t2 = t * t, t3 = t2 * t;
  const double u0 = static_cast<double>(k) / last, u1 = static_cast<double>(k + 1) / last;
  return (2 * t3 - 3 * t2 + 1) * u0 + (t3 - 2 * t2 + t) * h * table.du_ds[k] + (-2 * t3 + 3 * t2) * u1 +
         (t3 - t2) * h * table.du_ds[k + 1];
}

PathPoint Path::evaluate(int index, double s) const {
  if (segments.empty()) return start;
  const Segment& seg = segments[index];
  const double fraction = seg.length > 0.0 && s < seg.s_start + seg.length
                              ? std::clamp((s - seg.s_start) / seg.length, 0.0, 1.0)
                              : 1.0;
  const Curve& a = curves[seg.curve_a];
  if (!seg.is_blend()) {
    const double f = seg.fa0 + fraction * (seg.fa1 - seg.fa0);
    return {a.position(f), a.rotation(f)};
  }
  const Curve& b = curves[seg.curve_b];
  const double u = blend_parameter(blend_tables[seg.blend], fraction);
  const double fa = seg.fa0 + u * (seg.fa1 - seg.fa0);
  const double fb = seg.fb0 + u * (seg.fb1 - seg.fb0);
  const double w = blend_weight(u);
  const Eigen::Vector3d pa = a.position(fa);
  return {pa + w * (b.position(fb) - pa), slerp_short(a.rotation(fa), b.rotation(fb), w)};
}

PathPoint Path::end_point() const {
  if (segments.empty()) return start;
  return evaluate(static_cast<int>(segments.size()) - 1, length());
}

}  // namespace pkm::path
