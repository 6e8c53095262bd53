// NX NURBS/ records: the spline evaluated into line moves within the tolerance.
//
// NX writes (docs/cl-data.md):  GOTO/start  NURBS/  KNOT/k1,…,k12  KNOT/…  CNTRL/x,y,z  CNTRL/…
// and the curve ends at the next statement that is neither KNOT nor CNTRL (or at the end of the file). The
// only reading consistent with every real file is a clamped cubic B-spline (order 4) without weights, control
// polygon [the point before NURBS] + the CNTRLs, full knot vector [0,0,0,0] + the listed knots without their
// final 1 + [1,1,1,1]; so (#listed knots) = (#CNTRL) − 2, the listed knots rise and the last is 1.
//
// Decisions: the curve becomes feed moves at the feed in effect, every one carrying the NURBS statement's
// line (the moves of one span depend on four CNTRLs, no one line is theirs); each chord stays within
// kClNurbsChordToleranceMm of the curve (a bound on the distance, not a sampled estimate), and the last move
// ends exactly at the last CNTRL.
#include "program/cl_reader_nurbs.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>

namespace pkm::program {
namespace cl_nurbs_detail {

constexpr double kClNurbsChordToleranceMm = 0.001;
constexpr double kClKnotTolerance = 1e-7;  // NX writes knots to 7 decimals
constexpr int kClMaxBisections = 40;

/// One span's cubic in its local parameter s in [0, 1]: c0 + c1 s + c2 s² + c3 s³.
struct SpanCubic {
  Eigen::Matrix<double, 3, 4> c;
  Eigen::Vector3d second(double s) const { return 2.0 * c.col(2) + 6.0 * s * c.col(3); }
};

SpanCubic span_cubic(const ClCubicSpline& spline, double a, double b) {
  // The span is one cubic polynomial: four of its points give it exactly.
  Eigen::Matrix4d v;
  Eigen::Matrix<double, 3, 4> p;
  for (int i = 0; i < 4; ++i) {
    const double s = i / 3.0;
    v.row(i) << 1.0, s, s * s, s * s * s;
    p.col(i) = spline.at(a + s * (b - a));
  }
  SpanCubic out;
  out.c = (v.partialPivLu().solve(p.transpose())).transpose();
  return out;
}

// |C(s) − chord(s)| ≤ (s1 − s0)²/8 · max|C''| on [s0, s1], and |C''| (linear in s) is largest at an end.
void bisect_span(const SpanCubic& cubic, double s0, double s1, int depth, double tolerance,
                 std::vector<double>& out_s) {
  const double h = s1 - s0;
  const double bound = h * h / 8.0 * std::max(cubic.second(s0).norm(), cubic.second(s1).norm());
  if (bound <= tolerance || depth >= kClMaxBisections) {
    out_s.push_back(s1);
    return;
  }
  const double mid = 0.5 * (s0 + s1);
  bisect_span(cubic, s0, mid, depth + 1, tolerance, out_s);
  bisect_span(cubic, mid, s1, depth + 1, tolerance, out_s);
}

}  // namespace cl_nurbs_detail

Eigen::Vector3d ClCubicSpline::at(double t) const {
  const int n = static_cast<int>(points.size()) - 1;
  int k = static_cast<int>(std::upper_bound(knots.begin(), knots.end(), t) - knots.begin()) - 1;
  k = std::clamp(k, 3, n);
  std::array<Eigen::Vector3d, 4> d;
  for (int j = 0; j < 4; ++j) d[static_cast<std::size_t>(j)] = points[static_cast<std::size_t>(j + k - 3)];
  for (int r = 1; r <= 3; ++r) {
    for (int j = 3; j >= r; --j) {
      const auto i = static_cast<std::size_t>(j + k - 3);
      const double alpha = (t - knots[i]) / (knots[i + 4 - static_cast<std::size_t>(r)] - knots[i]);
      const auto uj = static_cast<std::size_t>(j);
      d[uj] = (1.0 - alpha) * d[uj - 1] + alpha * d[uj];
    }
  }
  return d[3];
}

std::vector<double> cl_spline_chord_parameters(const ClCubicSpline& spline, double tolerance_mm) {
  using namespace cl_nurbs_detail;
  const std::size_t n = spline.points.size() - 1;
  std::vector<double> out{spline.knots[3]};
  std::vector<double> local;
  for (std::size_t k = 3; k <= n; ++k) {
    const double a = spline.knots[k], b = spline.knots[k + 1];
    if (!(b > a)) continue;  // a repeated knot: no span
    const SpanCubic cubic = span_cubic(spline, a, b);
    local.clear();
    bisect_span(cubic, 0.0, 1.0, 0, tolerance_mm, local);
    for (const double s : local) out.push_back(s >= 1.0 ? b : a + s * (b - a));
  }
  return out;
}

bool ClReader::nurbs_collecting() const {
  return nurbs_ && nurbs_->collecting;
}

Status ClReader::nurbs(const ClStatement& s) {
  if (auto status = not_after_circle(s); !status) return status;
  if (cycle_active()) return error_at(s.at, "NURBS inside a CYCLE (CYCLE/OFF first)");
  if (rapid_next_) return error_at(s.at, "RAPID cannot apply to a NURBS curve");
  for (const ClArg& arg : s.args) {
    if (!arg.text.empty())
      return error_at(arg.at, "NURBS/ takes no values (its KNOT/ and CNTRL/ records follow)");
  }
  if (!nurbs_) nurbs_ = std::make_unique<ClNurbsState>();
  ClNurbsState& n = *nurbs_;
  n.collecting = true;
  n.at = s.at;
  n.start_mm = position_;
  n.knots.clear();
  n.control_mm.clear();
  return ok_status();
}

Status ClReader::nurbs_continue(const ClStatement& s, bool& consumed) {
  ClNurbsState& n = *nurbs_;
  consumed = true;
  if (s.word == "KNOT") {
    if (!n.control_mm.empty()) return error_at(s.at, "KNOT after CNTRL: a NURBS lists all its knots first");
    if (s.args.empty()) return error_at(s.at, "KNOT without values");
    for (const ClArg& arg : s.args) {
      double v = 0.0;
      if (auto status = number(arg, v); !status) return status;
      n.knots.push_back(v);
    }
    return ok_status();
  }
  if (s.word == "CNTRL") {
    if (s.args.size() != 3)
      return error_at(s.at, fmt::format("CNTRL takes x,y,z (3 values), got {}", s.args.size()));
    std::array<double, 3> v{};
    if (auto status = numbers(s, 0, 3, v.data()); !status) return status;
    if (n.control_mm.empty()) n.first_cntrl_at = s.at;
    n.control_mm.push_back(scale_ * Eigen::Vector3d(v[0], v[1], v[2]));
    return ok_status();
  }
  consumed = false;
  return nurbs_finish(s.at);
}

namespace cl_nurbs_detail {

/// The checks of NX's reading (see the file comment); an empty string when the record is one.
std::string nurbs_problem(const ClNurbsState& n) {
  const std::size_t cntrl = n.control_mm.size();
  if (cntrl < 3) return fmt::format("a NURBS (cubic) needs at least 3 CNTRL points, got {}", cntrl);
  if (n.knots.size() + 2 != cntrl)
    return fmt::format("a NURBS with {} CNTRL points lists {} knots (KNOT), {} expected (CNTRLs − 2)", cntrl,
                       n.knots.size(), cntrl - 2);
  if (std::abs(n.knots.back() - 1.0) > kClKnotTolerance)
    return fmt::format("the last knot of a NURBS must be 1, got {}", n.knots.back());
  double before = 0.0;
  int repeated = 1;
  for (std::size_t i = 0; i + 1 < n.knots.size(); ++i) {
    const double k = n.knots[i];
    if (!(k > 0.0 && k < 1.0)) return fmt::format("NURBS knot {} ({}) is not between 0 and 1", i + 1, k);
    if (k < before) return fmt::format("NURBS knots fall: {} after {}", k, before);
    repeated = k == before ? repeated + 1 : 1;
    if (repeated > 3)
      return fmt::format("NURBS knot {} repeated more than 3 times (a break in the curve)", k);
    before = k;
  }
  return {};
}

}  // namespace cl_nurbs_detail

Status ClReader::nurbs_finish(ClPosition) {
  using namespace cl_nurbs_detail;
  ClNurbsState& n = *nurbs_;
  n.collecting = false;
  if (const std::string why = nurbs_problem(n); !why.empty()) return error_at(n.at, why);
  ClCubicSpline spline;
  spline.points.reserve(n.control_mm.size() + 1);
  spline.points.push_back(n.start_mm);
  spline.points.insert(spline.points.end(), n.control_mm.begin(), n.control_mm.end());
  spline.knots = {0.0, 0.0, 0.0, 0.0};
  spline.knots.insert(spline.knots.end(), n.knots.begin(), n.knots.end() - 1);
  spline.knots.insert(spline.knots.end(), {1.0, 1.0, 1.0, 1.0});
  const std::vector<double> ts = cl_spline_chord_parameters(spline, kClNurbsChordToleranceMm);
  ClStatement at_nurbs;
  at_nurbs.word = "NURBS";
  at_nurbs.at = n.at;
  for (std::size_t i = 1; i < ts.size(); ++i) {
    const bool last = i + 1 == ts.size();
    CanonicalMove move = move_to(at_nurbs, MoveKind::line, last ? spline.points.back() : spline.at(ts[i]));
    if (auto status = set_feed(at_nurbs, move); !status) return status;
    if (auto status = emit(move, n.at); !status) return status;
  }
  position_ = spline.points.back();
  return ok_status();
}

}  // namespace pkm::program
