#pragma once
// Path tracking for the Stewart platform's Study-coordinate system (kinematics/stewart_system.hpp): one
// solution is followed while the parameters move along a straight segment from `from` (t = 0) to `to` (t =
// 1).
//
// Predictor: the Taylor coefficients of the path up to order 5 at the current point (each −J⁻¹ times a
// residual of the lower orders, all with one factorisation), evaluated as a Padé approximant of type (4, 1).
// Step size, chosen before the step (a priori): the predictor error estimated from the Taylor coefficients
// there (‖x₅ − x₄²/x₃‖·h⁵, the leading error of the (3, 1) approximant) aimed at the smaller of
// step_error_target and the first correction Newton would contract by contraction_target, given its
// contraction ω measured on the last steps (Timme 2021, "Mixed precision path tracking for polynomial
// homotopy continuation", sizes steps from such estimates). Corrector: Newton at the new t, accepted only
// when it contracts at once (the second correction at most a tenth of the first) and converges within three
// iterations (correction, or the error it leaves by the contraction seen, below the corrector tolerance);
// otherwise the step is resized from the error it showed. These two rules are what keeps a path from jumping
// onto a neighbouring one. Paths whose |x| grows past `infinity_norm` are reported as diverging (a solution
// at infinity of the target, e.g. the lost assembly modes of a special geometry); paths whose step falls
// below `min_step` stop where they are and are reported as failed, unless t is already within `endgame_start`
// of 1, where the endpoint is then refined by Newton and classified. The arithmetic is on pairs of doubles
// (kinematics/stewart_lanes.hpp), compiled twice: for the baseline processor and for AVX2 with fused
// multiply–add, chosen at run time (PathTrackOptions::wide_kernels); fixed sizes throughout: tracking
// allocates nothing.
#include "kinematics/stewart_system.hpp"

namespace pkm {

struct PathTrackOptions {
  /// The first step, or more where the estimated predictor error there stays within step_error_target.
  double initial_step = 0.05;
  double max_step = 0.3;
  double min_step = 1e-13;
  int max_steps = 4000;
  /// Newton stops when |Δx| ≤ corrector_tolerance·(1 + |x|), or when the error left after Δx, estimated
  /// from the contraction of the last two corrections (|Δx|²/|Δx_previous|), is at most half of that. Along
  /// the path this only has to stay well below the next step's predictor error (the end at t = 1 is refined
  /// to 1e-15 separately): 1e-5 saves the third iteration of most steps that 1e-7 needed.
  double corrector_tolerance = 1e-5;
  /// The predictor error (first Newton correction relative to 1 + |x|) that the step size aims at; a first
  /// correction above 0.05 rejects the step. Near other paths the contraction target binds first; 3e-3
  /// rather than 1e-3 takes 6–7 % fewer steps, with the same ends on 2000 general and 400 symmetric layouts.
  double step_error_target = 3e-3;
  /// The contraction θ = |Δx₁|/|Δx₀| of Newton's first two corrections that the step size aims at (the step
  /// is rejected above 0.1).
  double contraction_target = 0.02;
  /// |x| beyond which a path is diverging (a chart with |cᵀe| = 1 keeps real poses of a scaled problem far
  /// below this).
  double infinity_norm = 1e7;
  /// Within this distance of t = 1, a path whose remoteness (|g|/|e| or |e|²/|eᵀe|, about 1 at real poses of
  /// the scaled problem) is above divergence_norm and still grows like (1 − t)^(−0.2) or faster is reported
  /// at infinity without following it further.
  double divergence_zone = 1e-2;
  double divergence_norm = 50.0;
  /// Near t = 1 a path that stalls is refined at t = 1 instead of being reported as failed.
  double endgame_start = 1e-6;
  /// Run the tracker's AVX2/FMA kernels where the processor has them (core/wide_kernels.hpp: x86-64,
  /// detected at run time). false keeps the baseline kernels everywhere (the tests compare the two).
  bool wide_kernels = true;
};

enum class PathEnd {
  finite,       ///< reached t = 1; Newton converged there
  at_infinity,  ///< |x| diverged as t → 1: the target lost this solution
  failed        ///< the step size collapsed before t = 1 (reported, not hidden)
};

struct TrackedPath {
  StudyPoint x;
  PathEnd end = PathEnd::failed;
  int steps = 0;
  int rejected = 0;  ///< steps halved and tried again
  double t = 0.0;
  /// min |U_ii| / max |U_ii| of the LU factors of the Jacobian at the end: ≈ 0 at a singular (multiple or
  /// non-isolated) solution.
  double pivot_ratio = 0.0;
};

TrackedPath track_stewart_path(const StewartSystem& system, const StewartParameters& from,
                               const StewartParameters& to, const StudyPoint& start,
                               const PathTrackOptions& options = {});

/// Newton on the system at fixed parameters from `x` (in place): up to `iterations` steps, until the step is
/// below tolerance·(1 + |x|). Returns the last step's size relative to (1 + |x|), and the LU pivot ratio.
double refine_stewart_point(const StewartSystem& system, const StewartParameters& p, StudyPoint& x,
                            int iterations, double tolerance, double& pivot_ratio);

}  // namespace pkm
