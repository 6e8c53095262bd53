#include "kinematics/stewart_homotopy.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/complex_lu.hpp"

namespace pkm {
namespace {

using StudyLu = ComplexLu<8>;

// One straight parameter segment: p(t) = from + t·rate.
struct ParameterSegment {
  const StewartSystem& system;
  const StewartParameters& from;
  StewartParameters rate;
  StewartParameters at(double t) const { return from.lerp_rate(rate, t); }
};

// dx/dt at (t, x): −J⁻¹ ∂f/∂t.
StudyPoint path_velocity(const ParameterSegment& segment, double t, const StudyPoint& x, StudyJacobian& jx,
                         StudyLu& lu) {
  StudyPoint ft;
  segment.system.linearise(segment.at(t), &segment.rate, x, nullptr, jx, &ft);
  lu.compute(jx);
  return -lu.solve(ft);
}

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
  double h = options.initial_step;
  StudyJacobian jx;
  StudyLu lu;
  StudyPoint f;
  // dx/dt at the current point: from the corrector's last factorisation (a step of at most the corrector
  // tolerance away) once the path is under way, which saves one factorisation per step.
  StudyPoint k1 = path_velocity(segment, t, path.x, jx, lu);
  StudyPoint ft;
  while (t < 1.0 && path.steps < options.max_steps) {
    ++path.steps;
    h = std::min({h, options.max_step, 1.0 - t});
    const StudyPoint& x = path.x;
    // Runge–Kutta 4 predictor.
    const StudyPoint k2 = path_velocity(segment, t + 0.5 * h, x + 0.5 * h * k1, jx, lu);
    const StudyPoint k3 = path_velocity(segment, t + 0.5 * h, x + 0.5 * h * k2, jx, lu);
    const StudyPoint k4 = path_velocity(segment, t + h, x + h * k3, jx, lu);
    StudyPoint candidate = x + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    // Newton corrector at t + h.
    const double t_next = (1.0 - t - h) < 1e-15 ? 1.0 : t + h;
    const StewartParameters p = segment.at(t_next);
    bool converged = false;
    double first = 0.0;
    StudyPoint k1_next;
    for (int i = 0; i < 3; ++i) {
      system.linearise(p, &segment.rate, candidate, &f, jx, &ft);
      lu.compute(jx);
      const StudyPoint step = lu.solve(f);
      k1_next = -lu.solve(ft);
      candidate -= step;
      const double size = relative_step(step, candidate);
      if (!std::isfinite(size)) break;
      if (i == 0) {
        first = size;
        if (size > 0.05) break;  // the predictor landed too far from the path
      } else if (size > 0.1 * first && size > options.corrector_tolerance) {
        break;  // not contracting: too close to another path, or a singularity
      }
      if (size <= options.corrector_tolerance) {
        converged = true;
        break;
      }
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
      k1 = k1_next;
      t = t_next;
      if (diverging) {
        path.end = PathEnd::at_infinity;
        path.t = t;
        return path;
      }
      // The first correction is the predictor's error, O(h⁵) for Runge–Kutta 4: aim the next one at
      // step_error_target.
      const double growth = first > 0 ? std::pow(options.step_error_target / first, 0.2) : 2.0;
      h *= std::clamp(0.9 * growth, 0.5, 2.0);
      // (Remoteness alone is no test here: a complex path may pass near the isotropic cone on its way.)
      if (path.x.norm() > options.infinity_norm) {
        path.end = PathEnd::at_infinity;
        path.t = t;
        return path;
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
