#include "kinematics/stewart_homotopy.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/wide_kernels.hpp"
#include "kinematics/stewart_lanes.hpp"

namespace pkm {
namespace {
using stewart_lanes::LaneLu;
using stewart_lanes::Legs;
using stewart_lanes::Mat8;
using stewart_lanes::Vec8;

// The path's Taylor coefficients up to x_5 at each point: the predictor is the Padé approximant of type (4,
// 1) of x_0 … x_5, and x_5 also gives the step its error estimate (pade_error_coefficient).
constexpr int kTaylorOrder = 5;
using Taylor = std::array<Vec8, kTaylorOrder + 1>;
static_assert(kTaylorOrder == 5, "pade_error_coefficient reads x_3, x_4 and x_5 = back()");

// v^(1/5), the step size for a predictor error ∝ h⁵, once per step: std::pow took 2 % of the tracker's time.
// The estimate from the exponent bits (log₂ v ≈ bits/2⁵² − 1023), within 6.1 % of it, is refined by three
// Newton iterations for y⁵ = v, y ← (4y + v/y⁴)/5, each about squaring the relative error: within 1.5e-8 of
// std::pow over 1e-300 … 1e300 (10⁷ samples), far closer than a step size needs. Zero, infinite, NaN and
// subnormal v take std::pow.
double fifth_root(double v) {
  if (!(v >= std::numeric_limits<double>::min() && v <= std::numeric_limits<double>::max())) {
    return std::pow(v, 0.2);
  }
  constexpr std::uint64_t bias = (std::uint64_t{1023} << 52) / 5 * 4;
  double y = std::bit_cast<double>(std::bit_cast<std::uint64_t>(v) / 5 + bias);
  for (int i = 0; i < 3; ++i) {
    const double y2 = y * y;
    y = 0.8 * y + 0.2 * v / (y2 * y2);
  }
  return y;
}

double relative_step(const Vec8& step, const Vec8& x) {
  return step.norm() / (1.0 + x.norm());
}

// How far x is from any real pose, independently of the chart: |g|/|e| is half the distance of the platform
// from the origin (real poses of the scaled problem: about 1), and |e|²/|eᵀe| is 1 for a real rotation and
// infinite on the isotropic cone eᵀe = 0. The paths a special target loses run off along one of the two.
double pose_remoteness(const StudyPoint& x) {
  const double e = x.head<4>().norm();
  Complex ee = 0.0;
  for (int i = 0; i < 4; ++i) ee += x[i] * x[i];
  return std::max(x.tail<4>().norm() / e, e * e / std::abs(ee));
}
double pose_remoteness(const Vec8& x) {
  return pose_remoteness(x.point());
}

// The predictor: per coordinate, the Padé approximant of type (4, 1) of the Taylor polynomial, which follows
// a path towards a nearby pole (a solution running off to infinity, or a fast turn near another path) further
// than the polynomial does; the plain Taylor polynomial where the last two coefficients give no usable pole
// (a negligible second-to-last coefficient, or a pole so close beyond the step, |1 − h/pole| < 0.2, that the
// approximant would blow up). Two coordinates at a time, the choice made lane by lane.
Vec8 pade_prediction(const Taylor& taylor, double h) {
  using namespace stewart_lanes;
  constexpr int top = kTaylorOrder;
  const Lane one = {1.0, 1.0};
  Vec8 x;
  for (int q = 0; q < 4; ++q) {
    const CLane a = taylor[top - 1].pair[q], b = taylor.back().pair[q];  // .back(): taylor[top]
    const CLane polynomial = a + h * b;
    // 1 − h·b/a, and the approximant a/(1 − h·b/a); lanes where either is unusable keep the polynomial.
    const CLane q_pole = CLane{one, Lane{}} - h * quotient(b, a);
    const LaneMask usable = (abs2(a) > 1e-28 * (one + abs2(taylor[0].pair[q]))) & (abs2(q_pole) >= 0.04);
    CLane v = select(usable, quotient(a, q_pole), polynomial);
    for (int k = top - 2; k >= 0; --k) v = taylor[k].pair[q] + h * v;
    x.pair[q] = v;
  }
  return x;
}

// The predictor's error per h⁵, relative to 1 + |x|: ‖x_5 − x_4²/x_3‖ (per coordinate), the leading error of
// the Padé approximant of type (3, 1), whose expansion continues x_3 h³ + x_4 h⁴ + (x_4²/x_3) h⁵ + …. The (4,
// 1) approximant used is more accurate still, so this is an upper estimate. On the benchmark's paths it
// predicted the first Newton correction within a factor of 3 (2 standard deviations) where that correction
// was below 0.01, against a factor of 40 for the last step's error scaled by (h_new/h_old)⁵, which the step
// size used before: the paths' curvature changes by orders of magnitude within a few steps near t = 1.
double pade_error_coefficient(const Taylor& taylor) {
  using namespace stewart_lanes;
  const Lane one = {1.0, 1.0};
  Lane sum{};
  for (int q = 0; q < 4; ++q) {
    const CLane a = taylor[3].pair[q], b = taylor[4].pair[q];
    const CLane x5 = taylor.back().pair[q];
    const LaneMask usable = abs2(a) > 1e-28 * (one + abs2(taylor[0].pair[q]));
    const CLane d = select(usable, x5 - quotient(b * b, a), x5);
    sum += abs2(d);
  }
  return std::sqrt(sum[0] + sum[1]) / (1.0 + taylor[0].norm());
}

}  // namespace

namespace {

// The tracker's kernels as the baseline processor runs them.
struct BaselineKernels {
  static void linearise(const Legs& p, const Eigen::Vector4cd& chart, const Vec8& x, Vec8* f, Mat8& jx) {
    stewart_lanes::linearise(p, chart, x, f, jx);
  }
  static void linearise_in_last_order(const Legs& p, const Eigen::Vector4cd& chart, const Vec8& x, Vec8* f,
                                      LaneLu& lu) {
    stewart_lanes::linearise(p, chart, x, f, lu.columns_in_last_order());
  }
  static void factorise(LaneLu& lu) { lu.factorise(); }
  static bool factorise_in_last_order(LaneLu& lu) { return lu.factorise_in_last_order(); }
  static Vec8 solve(const LaneLu& lu, const Vec8& b) { return lu.solve(b); }
  static void taylor(const Legs& p, const Legs& rate, const LaneLu& lu, Vec8* coefficients) {
    stewart_lanes::path_taylor<kTaylorOrder>(p, rate, lu, coefficients);
  }
  static Vec8 predict(const Taylor& taylor, double h) { return pade_prediction(taylor, h); }
  static double error_coefficient(const Taylor& taylor) { return pade_error_coefficient(taylor); }
};

#if PKM_HAS_WIDE_KERNELS
// The same kernels compiled for AVX2 with fused multiply–add, each with everything it calls inlined
// (flatten): the pairs of doubles stay pairs, but a complex multiply–add takes two fused instructions instead
// of four, and the three-operand forms drop most of the register copies of SSE2's two-operand ones. Only
// what is inlined into these functions is compiled for AVX2: no function shared with the rest of the program
// (the library's inline functions, Eigen's) is emitted with these instructions, so the library still runs on
// any x86-64 processor, and these run only where the processor has them (wide_kernels_available).
struct WideKernels {
  PKM_WIDE_KERNEL static void linearise(const Legs& p, const Eigen::Vector4cd& chart, const Vec8& x, Vec8* f,
                                        Mat8& jx) {
    stewart_lanes::linearise(p, chart, x, f, jx);
  }
  PKM_WIDE_KERNEL static void linearise_in_last_order(const Legs& p, const Eigen::Vector4cd& chart,
                                                      const Vec8& x, Vec8* f, LaneLu& lu) {
    stewart_lanes::linearise(p, chart, x, f, lu.columns_in_last_order());
  }
  PKM_WIDE_KERNEL static void factorise(LaneLu& lu) { lu.factorise(); }
  PKM_WIDE_KERNEL static bool factorise_in_last_order(LaneLu& lu) { return lu.factorise_in_last_order(); }
  PKM_WIDE_KERNEL static Vec8 solve(const LaneLu& lu, const Vec8& b) { return lu.solve(b); }
  PKM_WIDE_KERNEL static void taylor(const Legs& p, const Legs& rate, const LaneLu& lu, Vec8* coefficients) {
    stewart_lanes::path_taylor<kTaylorOrder>(p, rate, lu, coefficients);
  }
  PKM_WIDE_KERNEL static Vec8 predict(const Taylor& taylor, double h) { return pade_prediction(taylor, h); }
  PKM_WIDE_KERNEL static double error_coefficient(const Taylor& taylor) {
    return pade_error_coefficient(taylor);
  }
};

#endif

// Newton at fixed parameters (refine_stewart_point), on Kernels.
template <class Kernels>
double refine_point(const Legs& legs, const Eigen::Vector4cd& chart, StudyPoint& x, int iterations,
                    double tolerance, double& pivot_ratio) {
  Vec8 point = Vec8::of(x), f;
  LaneLu lu;
  double last = 1.0;
  for (int i = 0; i < iterations; ++i) {
    Kernels::linearise(legs, chart, point, &f, lu.matrix());
    Kernels::factorise(lu);
    pivot_ratio = lu.pivot_ratio();
    const Vec8 step = Kernels::solve(lu, f);
    point -= step;
    last = relative_step(step, point);
    if (!std::isfinite(last)) break;
    if (last <= tolerance) break;
  }
  x = point.point();
  return last;
}

// Newton's contraction per unit of first correction, θ ≈ ω·|Δx₀| (Kantorovich: ω bounds the Jacobian's
// relative change), is measured on each step's first two corrections. The step's error target is the smaller
// of step_error_target and the first correction that would contract by contraction_target: near another path
// or a singularity ω is large and the corrector's basin small, and aiming the predictor at it there is what
// avoids most rejected steps (the old controller, aiming at a fixed error, had 6 per path).
double step_error_target(const PathTrackOptions& options, double omega) {
  return omega > 0 ? std::min(options.step_error_target, options.contraction_target / omega)
                   : options.step_error_target;
}

// The first step: sized from the start's Taylor coefficients, within the options' bounds.
double first_step(const PathTrackOptions& options, double coefficient) {
  double h = fifth_root(step_error_target(options, 0.0) / coefficient);
  if (!std::isfinite(h)) h = options.max_step;
  return std::max(std::min(h, options.max_step), std::min(options.initial_step, options.max_step));
}

// What the corrector saw at one step.
struct Correction {
  bool converged = false;
  double first = 0.0;  ///< the first correction's size, relative to 1 + |x|
  double theta = 0.0;  ///< the second correction's size over the first (0: no second correction)
};

// The corrector: up to three Newton iterations from the predicted `candidate` at parameters p, reusing the
// last factorisation's column order where it still pivots well. `lu` keeps the last factorisation (the next
// Taylor coefficients use it).
template <class Kernels>
Correction correct_step(const Legs& p, const Eigen::Vector4cd& chart, double tol, Vec8& candidate,
                        LaneLu& lu) {
  Correction c;
  Vec8 f;
  double previous = 0.0;
  for (int i = 0; i < 3; ++i) {
    // In the column order of the last factorisation, without a pivot search, where that order still
    // pivots well (LaneLu::factorise_in_last_order; 3–4 % of the factorisations do not).
    Kernels::linearise_in_last_order(p, chart, candidate, &f, lu);
    if (!Kernels::factorise_in_last_order(lu)) {
      Kernels::linearise(p, chart, candidate, &f, lu.matrix());
      Kernels::factorise(lu);
    }
    const Vec8 step = Kernels::solve(lu, f);
    candidate -= step;
    const double size = relative_step(step, candidate);
    if (!std::isfinite(size)) break;
    if (i == 0) {
      c.first = size;
      if (size > 0.05) break;  // the predictor landed too far from the path
    } else {
      if (i == 1) c.theta = size / c.first;
      if (size > 0.1 * c.first && size > tol) break;  // not contracting: too close to another path
    }
    // Converged when this correction, or the error it leaves (about size·(size/previous), Deuflhard's
    // estimate from the contraction seen, with a factor 0.5 for its roughness), is below the tolerance.
    if (size <= tol || (i > 0 && size * size <= 0.5 * tol * previous)) {
      c.converged = true;
      break;
    }
    previous = size;
  }
  return c;
}

// ω after a step: a larger one counts at once; a smaller one only halves the old (one easy step is no proof
// that the region is easy).
double updated_contraction(double omega, const Correction& c) {
  if (!(c.theta > 0 && c.first > 1e-12)) return omega;
  const double measured = c.theta / c.first;
  return c.converged ? std::max(measured, 0.5 * omega) : std::max(measured, omega);
}

// A path still growing fast near t = 1 is on its way to infinity: its remoteness grows like (1 − t)^(−k)
// there, with k ≈ 2 on every lost path of the 3-fold symmetric layouts (1.8–2.3 measured), while a path to a
// finite solution levels off. The upper bound 3 on k keeps an excursion past a nearby pole before t = 1 (a
// finite path passing close to infinity, whose growth rate relative to 1 − t is 5–130) from being taken for a
// divergence: the 2000 random geometries had 9 such paths reported at infinity before it, 1 after. Deciding
// it here saves the many small steps of a divergence.
bool diverging_step(const PathTrackOptions& options, const Vec8& x, const Vec8& candidate, double t,
                    double t_next) {
  if (!(t_next < 1.0 && 1.0 - t_next < options.divergence_zone &&
        candidate.norm() > options.divergence_norm)) {
    return false;
  }
  const double size_before = pose_remoteness(x), size_after = pose_remoteness(candidate);
  const double growth = std::log(size_after / size_before), approach = std::log((1.0 - t) / (1.0 - t_next));
  return size_after > options.divergence_norm && growth > 0.2 * approach && growth < 3.0 * approach;
}

// The step after a rejected one: resized from the error just measured at this h (the same Taylor data, so
// the measured coefficient is the better one), by a factor between 0.1 and 0.7.
double step_after_rejection(const PathTrackOptions& options, double omega, double h, double first,
                            double coefficient) {
  const double measured = first > 0 ? first / (h * h * h * h * h) : 0.0;
  double next = measured > 0 ? fifth_root(step_error_target(options, omega) / std::max(measured, coefficient))
                             : 0.5 * h;
  if (!std::isfinite(next)) next = 0.5 * h;
  return std::clamp(next, 0.1 * h, 0.7 * h);
}

// How a path that stopped at path.t (path.x) ends: refined at t = 1, or after a stalled approach to it (a
// singular endpoint, or one at infinity), or a collapse of the step size.
template <class Kernels>
void classify_end(const StewartParameters& to, const Eigen::Vector4cd& chart, const PathTrackOptions& options,
                  TrackedPath& path) {
  const double t = path.t;
  if (t >= 1.0) {
    const double last = refine_point<Kernels>(Legs::of(to), chart, path.x, 3, 1e-15, path.pivot_ratio);
    path.end = std::isfinite(last) ? PathEnd::finite : PathEnd::failed;
    return;
  }
  if (1.0 - t <= options.endgame_start) {
    // A stalled approach to t = 1: a singular endpoint, or one at infinity.
    StudyPoint end = path.x;
    const double last = refine_point<Kernels>(Legs::of(to), chart, end, 20, 1e-13, path.pivot_ratio);
    if (std::isfinite(last) && last < 1e-6 && pose_remoteness(end) < options.divergence_norm) {
      path.x = end;
      path.end = PathEnd::finite;
    } else {
      path.end = PathEnd::at_infinity;
    }
    return;
  }
  // A collapse of the step size close to t = 1 on a large |x| is a divergence the growth test did not catch.
  path.end = 1.0 - t < options.divergence_zone && pose_remoteness(path.x) > options.divergence_norm &&
                     path.x.norm() > options.divergence_norm
                 ? PathEnd::at_infinity
                 : PathEnd::failed;
}

// The tracker itself, on Kernels (BaselineKernels or WideKernels): track_stewart_path runs it with the
// kernels built for the baseline processor or, where the processor has them, for AVX2 and FMA. Each step:
// the Padé predictor, the corrector, and the next step size (a priori from the new point's Taylor
// coefficients after a converged step, from the measured error after a rejected one).
template <class Kernels>
TrackedPath follow_path(const StewartSystem& system, const StewartParameters& from,
                        const StewartParameters& to, const StudyPoint& start,
                        const PathTrackOptions& options) {
  const Legs origin = Legs::of(from), rate = Legs::of(to.minus(from));
  const Eigen::Vector4cd& chart = system.chart();
  TrackedPath path;
  Vec8 x = Vec8::of(start);
  double t = 0.0;
  LaneLu lu;
  Taylor taylor;
  Legs p = origin;
  Kernels::linearise(p, chart, x, nullptr, lu.matrix());
  Kernels::factorise(lu);
  taylor[0] = x;
  Kernels::taylor(p, rate, lu, taylor.data());
  double omega = 0.0;  // Newton's contraction per unit of first correction (step_error_target)
  double coefficient = Kernels::error_coefficient(taylor);
  double h = first_step(options, coefficient);
  while (t < 1.0 && path.steps < options.max_steps) {
    ++path.steps;
    h = std::min({h, options.max_step, 1.0 - t});
    Vec8 candidate = Kernels::predict(taylor, h);
    const double t_next = (1.0 - t - h) < 1e-15 ? 1.0 : t + h;
    p = origin.lerp_rate(rate, t_next);
    const Correction correction = correct_step<Kernels>(p, chart, options.corrector_tolerance, candidate, lu);
    omega = updated_contraction(omega, correction);
    if (!correction.converged) {
      ++path.rejected;
      h = step_after_rejection(options, omega, h, correction.first, coefficient);
      if (h < options.min_step) break;
      continue;
    }
    const bool diverging = diverging_step(options, x, candidate, t, t_next);
    x = candidate;
    t = t_next;
    if (diverging || x.norm() > options.infinity_norm) {
      path.x = x.point();
      path.end = PathEnd::at_infinity;
      path.t = t;
      return path;
    }
    if (t < 1.0) {
      // The Taylor coefficients at the new point, with the corrector's last factorisation: of the Jacobian
      // one correction (below the square root of the tolerance) away, which perturbs them far less than the
      // predictor error the step aims at. One factorisation per Newton iteration is thus shared with the
      // predictor. The next step is sized from them (a priori), at most 4 times this one.
      taylor[0] = x;
      Kernels::taylor(p, rate, lu, taylor.data());
      coefficient = Kernels::error_coefficient(taylor);
      const double next = fifth_root(step_error_target(options, omega) / coefficient);
      h = std::isfinite(next) ? std::min(next, 4.0 * h) : 2.0 * h;
    }
  }
  path.x = x.point();
  path.t = t;
  classify_end<Kernels>(to, chart, options, path);
  return path;
}

}  // namespace

double refine_stewart_point(const StewartSystem& system, const StewartParameters& p, StudyPoint& x,
                            int iterations, double tolerance, double& pivot_ratio) {
  return refine_point<BaselineKernels>(Legs::of(p), system.chart(), x, iterations, tolerance, pivot_ratio);
}

TrackedPath track_stewart_path(const StewartSystem& system, const StewartParameters& from,
                               const StewartParameters& to, const StudyPoint& start,
                               const PathTrackOptions& options) {
#if PKM_HAS_WIDE_KERNELS
  if (options.wide_kernels && wide_kernels_available())
    return follow_path<WideKernels>(system, from, to, start, options);
#endif
  return follow_path<BaselineKernels>(system, from, to, start, options);
}

}  // namespace pkm
