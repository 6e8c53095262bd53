#include "kinematics/stewart_homotopy.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "kinematics/complex_lu.hpp"

namespace pkm {
namespace {

using StudyLu = ComplexLu<8>;

// The predictor's order: Taylor coefficients up to x_4, from the Padé approximant of type (3, 1), whose error
// is O(h⁵) as Runge–Kutta 4's was. Order 5 took 9 % fewer steps for as many operations; order 3, 21 % more.
constexpr int kTaylorOrder = 4;

// One straight parameter segment: p(t) = from + t·rate.
struct ParameterSegment {
  const StewartSystem& system;
  const StewartParameters& from;
  StewartParameters rate;
  StewartParameters at(double t) const { return from.lerp_rate(rate, t); }
};

double relative_step(const StudyPoint& step, const StudyPoint& x) {
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

// The predictor: the Padé approximant of type (order − 1, 1) of each coordinate's Taylor polynomial, which
// follows a path towards a nearby pole (a solution running off to infinity, or a fast turn near another
// path) further than the polynomial does; the plain Taylor polynomial where the last two coefficients give no
// usable pole (a negligible second-to-last coefficient, or a pole so close beyond the step, |1 − h/pole| <
// 0.2, that the approximant would blow up).
StudyPoint pade_prediction(const std::array<StudyPoint, kTaylorOrder + 1>& taylor, double h) {
  using complex_arithmetic::abs2;
  using complex_arithmetic::mul;
  using complex_arithmetic::reciprocal;
  StudyPoint x;
  for (int c = 0; c < 8; ++c) {
    const Complex a = taylor[kTaylorOrder - 1][c], b = taylor.back()[c];
    Complex v = a + h * b;
    if (abs2(a) > 1e-28 * (1.0 + abs2(taylor[0][c]))) {
      const Complex q = 1.0 - h * mul(b, reciprocal(a));
      if (abs2(q) >= 0.04) v = mul(a, reciprocal(q));
    }
    for (int k = kTaylorOrder - 2; k >= 0; --k) v = taylor[k][c] + h * v;
    x[c] = v;
  }
  return x;
}

}  // namespace

double refine_stewart_point(const StewartSystem& system, const StewartParameters& p, StudyPoint& x,
                            int iterations, double tolerance, double& pivot_ratio) {
  StudyJacobian jx;
  StudyPoint f;
  StudyLu lu;
  double last = 1.0;
  for (int i = 0; i < iterations; ++i) {
    system.linearise(p, nullptr, x, &f, jx, nullptr);
    lu.compute(jx);
    pivot_ratio = lu.pivot_ratio();
    const StudyPoint step = lu.solve(f);
    x -= step;
    last = relative_step(step, x);
    if (!std::isfinite(last)) return last;
    if (last <= tolerance) break;
  }
  return last;
}

TrackedPath track_stewart_path(const StewartSystem& system, const StewartParameters& from,
                               const StewartParameters& to, const StudyPoint& start,
                               const PathTrackOptions& options) {
  const ParameterSegment segment{system, from, to.minus(from)};
  TrackedPath path;
  path.x = start;
  double t = 0.0;
  StudyJacobian jx;
  StudyLu lu;
  StudyPoint f;
  // The Taylor coefficients of the path at the current point, from a factorisation of the Jacobian there.
  std::array<StudyPoint, kTaylorOrder + 1> taylor;
  StewartParameters p = segment.at(t);
  system.linearise(p, nullptr, path.x, nullptr, jx, nullptr);
  lu.compute(jx);
  taylor[0] = path.x;
  system.path_taylor(p, segment.rate, lu, kTaylorOrder, taylor.data());
  // The first step where the last Taylor term reaches the error target (the paths start out smooth: a fixed
  // first step wastes a step or two growing), but at least initial_step.
  double h = options.initial_step;
  const double first_guess =
      std::pow(options.step_error_target * (1.0 + path.x.norm()) / taylor.back().norm(), 1.0 / kTaylorOrder);
  if (std::isfinite(first_guess)) h = std::max(h, std::min(first_guess, options.max_step));
  while (t < 1.0 && path.steps < options.max_steps) {
    ++path.steps;
    h = std::min({h, options.max_step, 1.0 - t});
    StudyPoint candidate = pade_prediction(taylor, h);
    // Newton corrector at t + h.
    const double t_next = (1.0 - t - h) < 1e-15 ? 1.0 : t + h;
    p = segment.at(t_next);
    bool converged = false;
    double first = 0.0, previous = 0.0;
    for (int i = 0; i < 3; ++i) {
      system.linearise(p, nullptr, candidate, &f, jx, nullptr);
      lu.compute(jx);
      const StudyPoint step = lu.solve(f);
      candidate -= step;
      const double size = relative_step(step, candidate);
      if (!std::isfinite(size)) break;
      if (i == 0) {
        first = size;
        if (size > 0.05) break;  // the predictor landed too far from the path
      } else if (size > 0.1 * first && size > options.corrector_tolerance) {
        break;  // not contracting: too close to another path, or a singularity
      }
      // Converged when this correction, or the error it leaves: Newton contracts at least as fast as the last
      // two corrections did, so what is left after this one is about size·(size/previous) (Deuflhard's
      // estimate; the factor 0.5 for its roughness). This saves the third factorisation of most steps, whose
      // correction would be far below the tolerance.
      if (size <= options.corrector_tolerance ||
          (i > 0 && size * size <= 0.5 * options.corrector_tolerance * previous)) {
        converged = true;
        break;
      }
      previous = size;
    }
    if (converged) {
      // A path still growing fast near t = 1 is on its way to infinity: |x| ~ (1 − t)^(−k) there, while a
      // path to a finite solution levels off. Deciding it here saves the many small steps of a divergence.
      const double size_before = pose_remoteness(path.x), size_after = pose_remoteness(candidate);
      const bool diverging = t_next < 1.0 && 1.0 - t_next < options.divergence_zone &&
                             size_after > options.divergence_norm &&
                             candidate.norm() > options.divergence_norm &&
                             std::log(size_after / size_before) > 0.2 * std::log((1.0 - t) / (1.0 - t_next));
      path.x = candidate;
      t = t_next;
      if (diverging) {
        path.end = PathEnd::at_infinity;
        path.t = t;
        return path;
      }
      // The first correction is the predictor's error, O(h^(order + 1)): aim the next one at
      // step_error_target.
      const double growth =
          first > 0 ? std::pow(options.step_error_target / first, 1.0 / (kTaylorOrder + 1)) : 2.0;
      h *= std::clamp(0.9 * growth, 0.5, 2.0);
      // (Remoteness alone is no test here: a complex path may pass near the isotropic cone on its way.)
      if (path.x.norm() > options.infinity_norm) {
        path.end = PathEnd::at_infinity;
        path.t = t;
        return path;
      }
      if (t < 1.0) {
        // The Taylor coefficients at the new point, with the corrector's last factorisation: of the Jacobian
        // one correction (below the square root of the tolerance) away, which perturbs them far less than the
        // predictor error the step aims at. One factorisation per step is thus shared by corrector and
        // predictor.
        taylor[0] = path.x;
        system.path_taylor(p, segment.rate, lu, kTaylorOrder, taylor.data());
      }
    } else {
      h *= 0.5;
      ++path.rejected;
      if (h < options.min_step) break;
    }
  }
  path.t = t;
  if (t >= 1.0) {
    const double last = refine_stewart_point(system, to, path.x, 3, 1e-15, path.pivot_ratio);
    path.end = std::isfinite(last) ? PathEnd::finite : PathEnd::failed;
    return path;
  }
  if (1.0 - t <= options.endgame_start) {
    // A stalled approach to t = 1: a singular endpoint, or one at infinity.
    StudyPoint x = path.x;
    const double last = refine_stewart_point(system, to, x, 20, 1e-13, path.pivot_ratio);
    if (std::isfinite(last) && last < 1e-6 && pose_remoteness(x) < options.divergence_norm) {
      path.x = x;
      path.end = PathEnd::finite;
    } else {
      path.end = PathEnd::at_infinity;
    }
    return path;
  }
  // A collapse of the step size close to t = 1 on a large |x| is a divergence the growth test did not catch.
  path.end = 1.0 - t < options.divergence_zone && pose_remoteness(path.x) > options.divergence_norm &&
                     path.x.norm() > options.divergence_norm
                 ? PathEnd::at_infinity
                 : PathEnd::failed;
  return path;
}

}  // namespace pkm
