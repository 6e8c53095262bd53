#include "path/path.hpp"

#include <algorithm>

namespace pkm::path {

int Path::find_segment(double s, int hint) const {
  const int n = static_cast<int>(segments.size());
  if (n == 0) return segment_base;
  int i = std::clamp(hint - segment_base, 0, n - 1);
  if (s < segments[i].s_start) {  // went backwards: binary search
    auto it = std::upper_bound(segments.begin(), segments.end(), s,
                               [](double value, const Segment& seg) { return value < seg.s_start; });
    return segment_base + std::max(0, static_cast<int>(it - segments.begin()) - 1);
  }
  while (i + 1 < n && s >= segments[i + 1].s_start) ++i;
  return segment_base + i;
}

void Path::drop_before(int index) {
  const int drop = std::min(index, segment_end()) - segment_base;
  if (drop <= 0 || 2 * drop < static_cast<int>(segments.size())) return;
  segments.erase(segments.begin(), segments.begin() + drop);
  segment_base += drop;
  if (segments.empty()) return;
  // Curves and tables are numbered in path order, so the first kept segment's are the first still used.
  const Segment& first = segments.front();
  const int first_curve = first.curve_a;
  curves.erase(curves.begin(), curves.begin() + (first_curve - curve_base));
  curve_base = first_curve;
  int first_blend = blend_base + static_cast<int>(blend_tables.size());
  for (const Segment& seg : segments) {
    if (seg.is_blend()) {
      first_blend = seg.blend;
      break;
    }
  }
  blend_tables.erase(blend_tables.begin(), blend_tables.begin() + (first_blend - blend_base));
  blend_base = first_blend;
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
  const Segment& seg = segment(index);
  const double fraction = seg.length > 0.0 && s < seg.s_start + seg.length
                              ? std::clamp((s - seg.s_start) / seg.length, 0.0, 1.0)
                              : 1.0;
  const Curve& a = curve(seg.curve_a);
  if (!seg.is_blend()) {
    const double f = seg.fa0 + fraction * (seg.fa1 - seg.fa0);
    return {a.position(f), a.rotation(f)};
  }
  const Curve& b = curve(seg.curve_b);
  const double u = blend_parameter(blend_table(seg.blend), fraction);
  const double fa = seg.fa0 + u * (seg.fa1 - seg.fa0);
  const double fb = seg.fb0 + u * (seg.fb1 - seg.fb0);
  const double w = blend_weight(u);
  const Eigen::Vector3d pa = a.position(fa);
  return {pa + w * (b.position(fb) - pa), slerp_short(a.rotation(fa), b.rotation(fb), w)};
}

PathPoint Path::end_point() const {
  if (segments.empty()) return start;
  return evaluate(segment_end() - 1, length());
}

}  // namespace pkm::path
