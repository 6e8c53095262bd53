#include "workspace/modes_margin.hpp"

#include <fmt/format.h>
#include <nlopt.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace pkm::workspace {
namespace {

using MarginVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
using MarginMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

// Points checked on the straight line from X0 to a found configuration (is it still X0's aspect?), and the
// bisections that then place where the line leaves it.
constexpr int kMarginLineChecks = 64;
constexpr int kMarginLineBisections = 60;
// Newton steps that put a configuration SLSQP left slightly off the surface det J = 0 onto it.
constexpr int kMarginPolishSteps = 8;
// The rays from X0 that look for a first singular configuration reach this many actuator scales (mm per mm
// of platform size, or rad), in steps growing by this factor.
constexpr double kMarginRayReach = 50.0;
constexpr double kMarginRayGrowth = 1.25;
// The search box about X0: this many times the nearest ray edge, per preconditioned coordinate.
constexpr double kMarginBoxFactor = 3.0;
// SLSQP starts besides X0: the nearest ray edges.
constexpr std::size_t kMarginRayStarts = 3;

bool margin_uses_twist_form(const Mechanism& mechanism, const Pose& pose, JacobianMatrix& twist) {
  return mechanism.controlled_axes().count() == 6 && mechanism.actuator_count() == 6 &&
         mechanism.twist_jacobian(pose, twist) && twist.rows() == 6 && twist.cols() == 6;
}

// det J in the margin's form. The Jacobian in controlled coordinates is divided by the volume its coordinates
// give the platform's motion, sqrt(det(TᵀT)) of the twists per coordinate T (rotations times the platform
// size L, so that both parts are lengths): a gimbal lock of the angle convention makes det J vanish with T's
// rank and is no singularity of the machine, while this ratio stays finite there.
bool margin_det_in_form(const Mechanism& mechanism, const Pose& pose, bool twist_form, double length_mm,
                        double& determinant) {
  if (twist_form) {
    JacobianMatrix twist;
    if (!mechanism.twist_jacobian(pose, twist) || twist.rows() != 6 || twist.cols() != 6) return false;
    determinant = twist.determinant();
    return std::isfinite(determinant);
  }
  auto jacobian = mechanism.jacobian(pose);
  if (!jacobian || jacobian->rows() != jacobian->cols() || jacobian->rows() == 0) return false;
  TwistBasis twists;
  if (!mechanism.controlled_twists(pose, twists) || twists.cols() != jacobian->cols()) return false;
  twists.bottomRows<3>() *= length_mm;
  const double volume = std::sqrt((twists.transpose() * twists).determinant());
  if (!(volume > 0.0)) return false;
  determinant = jacobian->determinant() / volume;
  return std::isfinite(determinant);
}

// The coordinates the search moves the pose in, u ∈ R^m about X0. A mechanism that controls all six
// coordinates moves by (Δp mm, ω·L) with R = exp(ω)·R0: no angle convention, so no gimbal lock of the
// coordinates can pass for a singularity. Reduced-DOF mechanisms move their controlled coordinates (angles
// times L) and complete the pose. L, the platform size, makes rotations comparable with translations.
class MarginSearchSpace {
 public:
  MarginSearchSpace(const Mechanism& mechanism, const Pose& start)
      : mechanism_(mechanism),
        start_(start),
        start_coordinates_(vector_from_pose(mechanism.convention(), start)),
        mask_(mechanism.controlled_axes()),
        all_six_(mask_.count() == 6),
        length_mm_(mechanism.platform_size_mm()) {}

  double length_mm() const { return length_mm_; }

  bool pose_at(const MarginVector& u, Pose& out) const {
    if (!u.allFinite()) return false;
    if (all_six_) {
      out.position_mm = start_.position_mm + u.head<3>();
      out.rotation = rotation_from_rotation_vector(u.tail<3>() / length_mm_) * start_.rotation;
      return true;
    }
    PoseVector c = start_coordinates_;
    int k = 0;
    for (int axis = 0; axis < 6; ++axis) {
      if (!mask_.controlled[static_cast<std::size_t>(axis)]) continue;
      c[axis] += axis < 3 ? u[k] : u[k] / length_mm_;
      ++k;
    }
    auto completed = mechanism_.complete_pose(pose_from_vector(mechanism_.convention(), c));
    if (!completed) return false;
    out = *completed;
    return true;
  }

 private:
  const Mechanism& mechanism_;
  Pose start_;
  PoseVector start_coordinates_;
  AxisMask mask_;
  bool all_six_;
  double length_mm_;
};

// The search in preconditioned coordinates y (u = P·y, P = (∂q/∂u at X0)⁻¹: near X0, y is the actuator
// change), minimising F(y) = ‖q − q0‖² subject to C(y) = det J/det J(X0) = 0.
struct MarginProblem {
  const Mechanism& mechanism;
  MarginSearchSpace space;
  MarginMatrix precondition;
  ActuatorVector start_actuators;
  double start_det = 1.0;
  bool twist_form = false;
  double step = 1e-4;     // central-difference step in y
  double penalty = 1e12;  // F where the pose is out of reach: NLopt wants finite values
  int evaluations = 0;

  bool pose_at(const MarginVector& y, Pose& pose) const {
    const MarginVector u = precondition * y;
    return space.pose_at(u, pose);
  }

  bool actuators_at(const MarginVector& y, ActuatorVector& q) const {
    Pose pose;
    if (!pose_at(y, pose)) return false;
    q.resize(mechanism.actuator_count());
    return mechanism.actuator_values(pose, q.data()) && q.allFinite();
  }

  bool distance_squared(const MarginVector& y, double& value) const {
    ActuatorVector q;
    if (!actuators_at(y, q)) return false;
    value = (q - start_actuators).squaredNorm();
    return true;
  }

  bool det_ratio(const MarginVector& y, double& ratio) const {
    Pose pose;
    double det = 0.0;
    if (!pose_at(y, pose) || !margin_det_in_form(mechanism, pose, twist_form, space.length_mm(), det))
      return false;
    ratio = det / start_det;
    return true;
  }

  // Central differences of `f` at y; one-sided where one side is out of reach, 0 where both are.
  template <class Function>
  void gradient(const MarginVector& y, double value, Function&& f, double* out) const {
    for (int i = 0; i < y.size(); ++i) {
      MarginVector plus = y, minus = y;
      plus[i] += step;
      minus[i] -= step;
      double fp = 0.0, fm = 0.0;
      const bool has_plus = f(plus, fp);
      const bool has_minus = f(minus, fm);
      out[i] = has_plus && has_minus ? (fp - fm) / (2 * step)
               : has_plus            ? (fp - value) / step
               : has_minus           ? (value - fm) / step
                                     : 0.0;
    }
  }
};

MarginVector margin_vector(unsigned n, const double* x) {
  MarginVector v(static_cast<int>(n));
  for (unsigned i = 0; i < n; ++i) v[static_cast<int>(i)] = x[i];
  return v;
}

double margin_objective(unsigned n, const double* x, double* grad, void* data) {
  auto& problem = *static_cast<MarginProblem*>(data);
  ++problem.evaluations;
  const MarginVector y = margin_vector(n, x);
  double value = 0.0;
  const auto f = [&](const MarginVector& at, double& out) { return problem.distance_squared(at, out); };
  if (!f(y, value)) {
    if (grad) std::fill(grad, grad + n, 0.0);
    return problem.penalty;
  }
  if (grad) problem.gradient(y, value, f, grad);
  return value;
}

double margin_constraint(unsigned n, const double* x, double* grad, void* data) {
  const auto& problem = *static_cast<const MarginProblem*>(data);
  const MarginVector y = margin_vector(n, x);
  double value = 0.0;
  const auto f = [&](const MarginVector& at, double& out) { return problem.det_ratio(at, out); };
  if (!f(y, value)) {
    // Out of reach: the objective's penalty already rejects the point; keep the constraint neutral.
    if (grad) std::fill(grad, grad + n, 0.0);
    return 1.0;
  }
  if (grad) problem.gradient(y, value, f, grad);
  return value;
}

struct MarginNloptDeleter {
  void operator()(nlopt_opt opt) const { nlopt_destroy(opt); }
};

// One SLSQP run from `start` within |y_i| ≤ box; returns where it ended (the best feasible point NLopt saw,
// or its last one).
MarginVector run_margin_slsqp(MarginProblem& problem, const MarginVector& start, double box,
                              const ModesMarginOptions& options) {
  const auto m = static_cast<unsigned>(start.size());
  std::unique_ptr<std::remove_pointer_t<nlopt_opt>, MarginNloptDeleter> opt(nlopt_create(NLOPT_LD_SLSQP, m));
  nlopt_set_min_objective(opt.get(), margin_objective, &problem);
  // A box about X0 keeps the search from running off towards the singular configurations at infinity.
  nlopt_set_lower_bounds1(opt.get(), -box);
  nlopt_set_upper_bounds1(opt.get(), box);
  nlopt_add_equality_constraint(opt.get(), margin_constraint, &problem, options.singular_det_ratio);
  nlopt_set_xtol_rel(opt.get(), options.step_tolerance_rel);
  nlopt_set_maxeval(opt.get(), options.max_evaluations);
  std::vector<double> x(start.data(), start.data() + start.size());
  double value = 0.0;
  // Round-off and evaluation limits end a run as well as convergence does: x is the best point so far,
  // judged below like any other.
  nlopt_optimize(opt.get(), x.data(), &value);
  return margin_vector(m, x.data());
}

// Newton steps along ∇C onto C = 0 (the smallest move in y that zeroes the linearised constraint).
void margin_polish_onto_surface(const MarginProblem& problem, MarginVector& y, double tolerance) {
  for (int k = 0; k < kMarginPolishSteps; ++k) {
    double c = 0.0;
    if (!problem.det_ratio(y, c) || std::abs(c) <= tolerance) return;
    MarginVector g(y.size());
    const auto f = [&](const MarginVector& at, double& out) { return problem.det_ratio(at, out); };
    problem.gradient(y, c, f, g.data());
    const double g2 = g.squaredNorm();
    if (!(g2 > 0.0)) return;
    y -= (c / g2) * g;
  }
}

// Whether y is on the surface det J = 0 (within the tolerance) and in reach.
bool margin_on_surface(const MarginProblem& problem, const MarginVector& y, double tolerance) {
  double c = 0.0;
  ActuatorVector q;
  return problem.det_ratio(y, c) && problem.actuators_at(y, q) && std::abs(c) <= tolerance;
}

// Where the straight line from X0 (y = 0) to y first leaves X0's aspect: the largest t ≤ 1 such that C > 0 on
// [0, t); 1 when the whole line up to its end stays in the aspect.
double margin_aspect_exit(const MarginProblem& problem, const MarginVector& y) {
  const auto regular = [&](double t) {
    double c = 0.0;
    return problem.det_ratio(t * y, c) && c > 0.0;
  };
  for (int k = 1; k < kMarginLineChecks; ++k) {
    const double t = static_cast<double>(k) / kMarginLineChecks;
    if (regular(t)) continue;
    double inside = static_cast<double>(k - 1) / kMarginLineChecks, outside = t;
    for (int b = 0; b < kMarginLineBisections; ++b) {
      const double mid = 0.5 * (inside + outside);
      (regular(mid) ? inside : outside) = mid;
    }
    return outside;
  }
  return 1.0;
}

// The first singular configuration on the ray from X0 (y = 0) along the unit vector `direction`: a point of
// the surface det J = 0 on the edge of X0's aspect. The ray is stepped geometrically from a thousandth of the
// actuator scale up to kMarginRayReach times it, and the crossing bisected. False where the ray leaves the
// reachable poses first, or runs out before det J changes sign.
bool margin_ray_edge(const MarginProblem& problem, const MarginVector& direction, double scale,
                     double tolerance, MarginVector& out) {
  const auto regular = [&](double t) {
    double c = 0.0;
    return problem.det_ratio(t * direction, c) && c > 0.0;
  };
  double inside = 0.0, outside = 1e-3 * scale;
  bool crossed = false;
  while (outside <= kMarginRayReach * scale) {
    if (!regular(outside)) {
      crossed = true;
      break;
    }
    inside = outside;
    outside *= kMarginRayGrowth;
  }
  if (!crossed) return false;
  for (int b = 0; b < kMarginLineBisections; ++b) {
    const double mid = 0.5 * (inside + outside);
    (regular(mid) ? inside : outside) = mid;
  }
  out = outside * direction;
  margin_polish_onto_surface(problem, out, tolerance);
  return margin_on_surface(problem, out, tolerance);
}

// The best singular configuration of X0's aspect seen so far: every one found by a ray from X0 or accepted
// from the search bounds the margin from above.
struct MarginCandidate {
  MarginVector y;
  double distance = INFINITY;  // ‖q(y) − q0‖
  bool local_minimum = false;  // SLSQP's converged point (otherwise an edge point on a line from X0)
  bool offer(const MarginProblem& problem, const MarginVector& at, bool converged) {
    ActuatorVector q;
    if (!problem.actuators_at(at, q)) return false;
    const double d = (q - problem.start_actuators).norm();
    if (!(d < distance)) return false;
    y = at;
    distance = d;
    local_minimum = converged;
    return true;
  }
};

Status check_margin_options(const ModesMarginOptions& o) {
  if (!(o.singular_det_ratio > 0.0 && o.singular_det_ratio < 1.0))
    return make_error(ErrorCode::bad_input,
                      fmt::format("singular_det_ratio must be > 0 and < 1, got {}", o.singular_det_ratio));
  if (!(o.step_tolerance_rel > 0.0 && o.step_tolerance_rel < 1.0))
    return make_error(ErrorCode::bad_input,
                      fmt::format("step_tolerance_rel must be > 0 and < 1, got {}", o.step_tolerance_rel));
  if (o.max_evaluations < 1)
    return make_error(ErrorCode::bad_input,
                      fmt::format("max_evaluations must be at least 1, got {}", o.max_evaluations));
  if (!(o.gradient_step_fraction > 0.0 && o.gradient_step_fraction < 1e-2))
    return make_error(
        ErrorCode::bad_input,
        fmt::format("gradient_step_fraction must be > 0 and < 0.01, got {}", o.gradient_step_fraction));
  if (o.max_restarts < 0)
    return make_error(ErrorCode::bad_input, fmt::format("max_restarts must be ≥ 0, got {}", o.max_restarts));
  return ok_status();
}

}  // namespace

bool margin_determinant(const Mechanism& mechanism, const Pose& pose, double& determinant) {
  JacobianMatrix twist;
  const bool twist_form = margin_uses_twist_form(mechanism, pose, twist);
  if (twist_form) {
    determinant = twist.determinant();
    return std::isfinite(determinant);
  }
  return margin_det_in_form(mechanism, pose, false, mechanism.platform_size_mm(), determinant);
}

namespace {

// ∂q/∂u at X0 by central differences: the preconditioner, and whether X0 is itself singular. False at the
// edge of the reachable poses, where a neighbour has no actuator values.
bool margin_actuator_jacobian(const Mechanism& mechanism, const MarginProblem& problem, double u_step,
                              MarginMatrix& dq_du) {
  const int n = static_cast<int>(dq_du.rows()), m = static_cast<int>(dq_du.cols());
  for (int i = 0; i < m; ++i) {
    MarginVector plus = MarginVector::Zero(m), minus = MarginVector::Zero(m);
    plus[i] = u_step;
    minus[i] = -u_step;
    Pose pose_plus, pose_minus;
    ActuatorVector q_plus(n), q_minus(n);
    if (!problem.space.pose_at(plus, pose_plus) || !problem.space.pose_at(minus, pose_minus) ||
        !mechanism.actuator_values(pose_plus, q_plus.data()) ||
        !mechanism.actuator_values(pose_minus, q_minus.data()))
      return false;
    dq_du.col(i) = (q_plus - q_minus) / (2 * u_step);
  }
  return true;
}

// Rays from X0: along −∇C (where det J falls fastest per actuator change) and along ± each preconditioned
// coordinate (near X0, one actuator moving alone). Their first singular configurations bound the margin
// (offered to `best`); returned nearest first as (‖Δq‖, y).
std::vector<std::pair<double, MarginVector>> margin_ray_edges(MarginProblem& problem, int m,
                                                              double actuator_scale, double tolerance,
                                                              const ActuatorVector& q0,
                                                              MarginCandidate& best) {
  std::vector<std::pair<double, MarginVector>> edges;
  MarginVector g(m);
  const auto f = [&](const MarginVector& at, double& value) { return problem.det_ratio(at, value); };
  problem.gradient(MarginVector::Zero(m), 1.0, f, g.data());
  std::vector<MarginVector> directions;
  if (g.norm() > 0.0) directions.push_back(-g.normalized());
  for (int i = 0; i < m; ++i) {
    for (double sign : {1.0, -1.0}) directions.push_back(sign * MarginVector::Unit(m, i));
  }
  for (const MarginVector& direction : directions) {
    MarginVector edge;
    ActuatorVector q;
    if (margin_ray_edge(problem, direction, actuator_scale, tolerance, edge) &&
        problem.actuators_at(edge, q)) {
      edges.emplace_back((q - q0).norm(), edge);
      best.offer(problem, edge, false);
    }
  }
  std::sort(edges.begin(), edges.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return edges;
}

// SLSQP from `first` within the box; where it ends off the surface, or the line from X0 to its end leaves
// X0's aspect first through det J = 0, that singular configuration of the aspect is a bound and the next
// start.
void margin_search_from(MarginProblem& problem, const MarginVector& first, double box, double tolerance,
                        const ModesMarginOptions& options, MarginCandidate& best,
                        AssemblyModeMargin& result) {
  MarginVector start = first;
  for (int attempt = 0;; ++attempt) {
    MarginVector y = run_margin_slsqp(problem, start, box, options);
    margin_polish_onto_surface(problem, y, tolerance);
    const double exit = margin_aspect_exit(problem, y);
    if (exit >= 1.0 && margin_on_surface(problem, y, tolerance)) {
      best.offer(problem, y, true);
      return;
    }
    MarginVector edge = exit * y;
    margin_polish_onto_surface(problem, edge, tolerance);
    if (!(exit < 1.0 && margin_on_surface(problem, edge, tolerance))) return;
    best.offer(problem, edge, false);
    if (attempt == options.max_restarts) return;
    start = edge;
    ++result.restarts;
  }
}

// The best singular configuration found, as the result's margin, or the note why there is none or it is a
// bound.
void margin_result_from(const MarginCandidate& best, MarginProblem& problem, const Mechanism& mechanism,
                        double actuator_scale, AssemblyModeMargin& result) {
  result.evaluations = problem.evaluations;
  if (!std::isfinite(best.distance)) {
    result.note = fmt::format(
        "no singular configuration found from this pose: no ray from it meets one within {:g} {} and no "
        "search converged onto one ({} evaluations)",
        kMarginRayReach * actuator_scale, mechanism.actuators_are_angles() ? "rad" : "mm",
        problem.evaluations);
    return;
  }
  if (!best.local_minimum) {
    result.note =
        "the search did not converge to a local minimum in this pose's aspect: the margin is the distance to "
        "the nearest singular configuration found on a line from the pose, an upper bound";
  }
  ActuatorVector q;
  Pose singular;
  problem.pose_at(best.y, singular);
  problem.actuators_at(best.y, q);
  result.found = true;
  result.singular_pose = singular;
  result.singular_actuators = q;
  result.margin_mm = (q - result.actuators).norm();
  problem.det_ratio(best.y, result.det_ratio);
}

}  // namespace

Result<AssemblyModeMargin> assembly_mode_margin(const Mechanism& mechanism, const Pose& pose,
                                                const ModesMarginOptions& options) {
  if (Status valid = check_margin_options(options); !valid) return valid.error();
  const int n = mechanism.actuator_count();
  const int m = mechanism.controlled_axes().count();
  if (n != m) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("the assembly-mode margin needs a square actuator Jacobian; this {} has {} "
                                  "actuators for {} controlled coordinates",
                                  to_string(mechanism.type()), n, m));
  }
  auto completed = mechanism.complete_pose(pose);
  if (!completed) return completed.error();
  auto q0 = mechanism.inverse(*completed);
  if (!q0) return q0.error();

  AssemblyModeMargin result;
  result.pose = *completed;
  result.actuators = *q0;
  JacobianMatrix twist;
  result.twist_form = margin_uses_twist_form(mechanism, *completed, twist);

  MarginProblem problem{mechanism, MarginSearchSpace(mechanism, *completed), {}, *q0, 1.0, result.twist_form};
  // Actuator-sized quantities: mm for lengths and carriage positions, 1 rad for angular actuators.
  const double actuator_scale = mechanism.actuators_are_angles() ? 1.0 : problem.space.length_mm();
  problem.penalty = 1e6 * actuator_scale * actuator_scale;

  MarginMatrix dq_du(n, m);
  if (!margin_actuator_jacobian(mechanism, problem,
                                options.gradient_step_fraction * problem.space.length_mm(), dq_du)) {
    // At the edge of the reachable poses there is no Jacobian to precondition with: no margin, no failure.
    result.note = "the pose is at the edge of the reachable poses: its neighbours have no actuator values";
    return result;
  }
  const Eigen::JacobiSVD<MarginMatrix> svd(dq_du);
  const auto& sigma = svd.singularValues();
  double det0 = 0.0;
  const bool has_det =
      margin_det_in_form(mechanism, *completed, result.twist_form, problem.space.length_mm(), det0);
  if (!has_det || !(sigma.minCoeff() > options.singular_det_ratio * sigma.maxCoeff()) || det0 == 0.0) {
    // X0 is singular: its mode meets another one right here.
    result.found = true;
    result.margin_mm = 0.0;
    result.singular_pose = *completed;
    result.singular_actuators = *q0;
    result.det_ratio = 0.0;
    return result;
  }
  problem.start_det = det0;
  problem.precondition = dq_du.inverse();
  problem.step = options.gradient_step_fraction * actuator_scale;

  // The rays' first singular configurations are starts for SLSQP besides X0 itself: from X0 alone its first,
  // linearised step may overshoot across the surface into another basin.
  const double tolerance = options.singular_det_ratio;
  MarginCandidate best;
  const auto edges = margin_ray_edges(problem, m, actuator_scale, tolerance, *q0, best);
  std::vector<MarginVector> starts = {MarginVector::Zero(m)};
  const double box =
      edges.empty() ? kMarginRayReach * actuator_scale : kMarginBoxFactor * edges[0].second.norm();
  for (std::size_t k = 0; k < edges.size() && starts.size() <= kMarginRayStarts; ++k) {
    if (edges[k].second.lpNorm<Eigen::Infinity>() <= box) starts.push_back(edges[k].second);
  }
  for (const MarginVector& first : starts)
    margin_search_from(problem, first, box, tolerance, options, best, result);
  margin_result_from(best, problem, mechanism, actuator_scale, result);
  return result;
}

}  // namespace pkm::workspace
