#include "interpolation/quantisation/discreteness_corrector.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "interpolation/quantisation/remainder_quantizer.hpp"
#include "kinematics/fixed_lu.hpp"

namespace pkm::interpolation {

namespace {

// The inverse of the actuator Jacobian, J⁻¹ = ∂(coordinates)/∂(actuators). A six-actuator machine takes the
// fixed-size LU of the FK solver: Eigen's dynamic-size PartialPivLU and its solve against the identity went
// through blocked matrix kernels and cost a third of the whole period (profiled with callgrind:
// 28 000 of 42 000 instructions). Singular J gives non-finite values either way.
void actuator_sensitivity(const JacobianMatrix& jacobian, JacobianMatrix& sensitivity) {
  if (jacobian.rows() == 6 && jacobian.cols() == 6) {
    FixedLu<6> lu;
    lu.compute(Eigen::Matrix<double, 6, 6>(jacobian));
    for (int j = 0; j < 6; ++j) sensitivity.col(j) = lu.solve(FixedLu<6>::Vector::Unit(j));
    return;
  }
  const Eigen::PartialPivLU<JacobianMatrix> lu(jacobian);
  sensitivity = lu.solve(JacobianMatrix::Identity(jacobian.rows(), jacobian.rows()));
}

}  // namespace

DiscretenessCorrector::DiscretenessCorrector(const Machine& machine, const path::Path& path,
                                             const ContourGauge& gauge, const CorrectorSettings& settings)
    : machine_(machine),
      path_(path),
      gauge_(gauge),
      settings_(settings),
      count_(machine.mechanism->actuator_count()),
      end_tracker_(machine, machine.mechanism->home()),
      probe_tracker_(machine, machine.mechanism->home()) {
  const AxisMask axes = machine.mechanism->controlled_axes();
  for (int axis = 0; axis < 6; ++axis) {
    if (axes.controlled[axis]) coordinate_axis_[coordinates_++] = axis;
  }
}

Status DiscretenessCorrector::fail(const CarrierPeriod& period, const char* where) const {
  return Error{ErrorCode::not_converged,
               fmt::format("period {} (t = {:.4f} s): forward kinematics failed at the {} of the period",
                           period.index, period.time_s, where)};
}

Status DiscretenessCorrector::start(const std::array<double, kMaxActuators>& ideal_start) {
  position_ = truncated_steps(ideal_start, count_, settings_.step);
  std::array<double, kMaxActuators> values{};
  for (int j = 0; j < count_; ++j) values[j] = static_cast<double>(position_[j]) * settings_.step;
  Pose pose;
  PoseTracker first(machine_, machine_.mechanism->home());
  if (!first.solve(values.data(), pose)) {
    return Error{ErrorCode::not_converged, "forward kinematics failed at the start positions"};
  }
  end_tracker_.reset(pose);
  issued_point_mm_ = pose.position_mm;
  probe_tracker_.reset(pose);
  end_hint_ = middle_hint_ = 0;
  return ok_status();
}

bool DiscretenessCorrector::linearise(PoseTracker& tracker, const std::array<double, kMaxActuators>& values,
                                      Linearisation& out) {
  Pose pose;
  ++statistics_.fk_solves;
  if (!tracker.solve(values.data(), pose)) return false;
  auto jacobian = machine_.mechanism->jacobian(pose);
  ++statistics_.jacobians;
  if (!jacobian || jacobian->rows() != count_ || jacobian->cols() != coordinates_) return false;
  // ∂(coordinates)/∂(actuators): the FK sensitivities of §5.2.2 (eq. 144) and §5.2.5.
  JacobianMatrix sensitivity(coordinates_, count_);
  actuator_sensitivity(*jacobian, sensitivity);
  out.point_mm = pose.position_mm;
  // The angles matter only to the orientation criterion (three atan2 a period otherwise wasted).
  out.angles = settings_.orientation_criterion
                   ? angles_from_rotation(machine_.mechanism->convention(), pose.rotation)
                   : Eigen::Vector3d::Zero();
  const double share = settings_.step;
  for (int j = 0; j < count_; ++j) {
    out.point_per_step[j].setZero();
    out.angles_per_step[j].setZero();
    for (int c = 0; c < coordinates_; ++c) {
      const int axis = coordinate_axis_[c];
      if (axis < 3) {
        out.point_per_step[j][axis] = sensitivity(c, j) * share;
      } else {
        out.angles_per_step[j][axis - 3] = sensitivity(c, j) * share;
      }
    }
  }
  return true;
}

struct DiscretenessCorrector::PeriodGoal {
  std::array<std::int64_t, kMaxActuators> floor_position{};
  std::array<double, kMaxActuators> end_values{};     ///< the actuators' all-floor values at the period's end
  std::array<double, kMaxActuators> middle_values{};  ///< and half way from the issued state
  path::PathPoint end_point, middle_point;
  Eigen::Vector3d end_tangent, middle_tangent;
  double s_end = 0.0, s_middle = 0.0;
  double end_ahead = 0.0, middle_ahead = 0.0;  ///< the path left after them
  Eigen::Vector3d required_angles;             ///< with the orientation criterion
};

struct DiscretenessCorrector::Choice {
  unsigned combinations = 0;
  unsigned best_feasible = 0, best_oriented = 0, best_any = 0;
  double best_feasible_error = std::numeric_limits<double>::infinity();
  double best_oriented_deviation = std::numeric_limits<double>::infinity();
  double best_any_error = std::numeric_limits<double>::infinity();
  double chosen_end_error = 0.0, chosen_middle_error = 0.0;
  double any_end_error = 0.0, any_middle_error = 0.0;

  explicit Choice(int count)
      : combinations(1u << count), best_feasible(combinations), best_oriented(combinations) {}
  // One combination of extra steps (`bits`) with its contour errors at the period's end and middle and its
  // orientation's deviation: the best within ρ_max at the middle, and with the orientation criterion the one
  // nearest the programmed orientation within a share of it; the smallest error whatever it is as a fallback.
  void consider(const CorrectorSettings& settings, unsigned bits, double end_error, double middle_error,
                double angle_deviation) {
    const double worse = std::max(end_error, middle_error);
    if (worse < best_any_error) {
      best_any_error = worse, best_any = bits, any_end_error = end_error, any_middle_error = middle_error;
    }
    if (middle_error <= settings.rho_max_mm && end_error < best_feasible_error) {
      best_feasible_error = end_error, best_feasible = bits;
      if (!settings.orientation_criterion) chosen_end_error = end_error, chosen_middle_error = middle_error;
    }
    if (settings.orientation_criterion && worse <= settings.orientation_contour_share * settings.rho_max_mm &&
        angle_deviation < best_oriented_deviation) {
      best_oriented_deviation = angle_deviation, best_oriented = bits;
      chosen_end_error = end_error, chosen_middle_error = middle_error;
    }
  }
};

DiscretenessCorrector::PeriodGoal DiscretenessCorrector::period_goal(const CarrierPeriod& period) {
  PeriodGoal goal;
  const double step = settings_.step;
  for (int j = 0; j < count_; ++j) {
    goal.floor_position[j] = static_cast<std::int64_t>(std::floor(period.target[j] / step));
    goal.end_values[j] = static_cast<double>(goal.floor_position[j]) * step;
    goal.middle_values[j] = 0.5 * static_cast<double>(position_[j] + goal.floor_position[j]) * step;
  }
  // The programmed path near the period's end and middle: points and tangents of the contour measure. The
  // segment hints carry over from the previous period: searched from the path's start, the cost would grow
  // with the line number (a long program's last periods would walk all its segments).
  goal.s_end = period.s_end;
  goal.end_point = path_.evaluate(period.s_end, end_hint_);
  // At rest and at the path's end the tool must be at the point, not anywhere on its tangent: there the
  // distance to the point is the error (a zero tangent makes line_distance the full distance).
  const double length = path_.length();
  goal.end_ahead = length - period.s_end;
  const bool at_point = period.s_end - period.s_start <= 1e-12 || period.s_end >= length;
  goal.end_tangent = at_point ? Eigen::Vector3d::Zero() : gauge_.tangent(period.s_end, end_hint_);
  goal.s_middle = 0.5 * (period.s_start + period.s_end);
  goal.middle_ahead = length - goal.s_middle;
  goal.middle_point = path_.evaluate(goal.s_middle, middle_hint_);
  goal.middle_tangent = period.s_end - period.s_start <= 1e-12 ? Eigen::Vector3d::Zero()
                                                               : gauge_.tangent(goal.s_middle, middle_hint_);
  goal.required_angles =
      settings_.orientation_criterion
          ? angles_from_rotation(machine_.mechanism->convention(), goal.end_point.rotation.toRotationMatrix())
          : Eigen::Vector3d::Zero();
  return goal;
}

void DiscretenessCorrector::choose_linearised(const PeriodGoal& goal, const Linearisation& end,
                                              Choice& choice) const {
  // The middle needs only its point, and the drives pass it half way between the issued state and this
  // one: the midpoint of the two tool points, off the FK of the middle lengths by |Δp|²/(8·L) for a
  // period's motion Δp on struts of length L (0.1 mm on 500 mm: 2.5e-6 mm, the order the linearisation
  // itself neglects). Its sensitivities are the end's at half the share (the Jacobians a period apart
  // differ by ≲ 1e-3 relative). A second FK, Jacobian and inverse would cost 40 % of the period.
  const Eigen::Vector3d middle_point_mm = 0.5 * (issued_point_mm_ + end.point_mm);
  // Gray-code walk: each combination differs from the previous one in one actuator's extra step. The
  // offsets from the path points move by the (masked) per-step displacements.
  std::array<Eigen::Vector3d, kMaxActuators> offset_per_step;
  for (int j = 0; j < count_; ++j) offset_per_step[j] = gauge_.mask(end.point_per_step[j]);
  Eigen::Vector3d end_offset = gauge_.mask(end.point_mm - goal.end_point.position_mm);
  Eigen::Vector3d middle_offset = gauge_.mask(middle_point_mm - goal.middle_point.position_mm);
  Eigen::Vector3d angles = end.angles;
  unsigned gray = 0;
  for (unsigned k = 0; k < choice.combinations; ++k) {
    if (k > 0) {
      const int j = std::countr_zero(k);
      const double sign = (gray >> j) & 1u ? -1.0 : 1.0;
      gray ^= 1u << j;
      end_offset += sign * offset_per_step[j];
      middle_offset += (0.5 * sign) * offset_per_step[j];
      angles += sign * end.angles_per_step[j];
    }
    choice.consider(
        settings_, gray,
        ContourGauge::line_distance(end_offset, goal.end_tangent, goal.s_end, goal.end_ahead),
        ContourGauge::line_distance(middle_offset, goal.middle_tangent, goal.s_middle, goal.middle_ahead),
        (angles - goal.required_angles).squaredNorm());
  }
}

Status DiscretenessCorrector::choose_exact(const CarrierPeriod& period, const PeriodGoal& goal,
                                           Choice& choice) {
  // Reference: FK of every combination, the exact nearest path point.
  const Pose anchor = end_tracker_.last();
  for (unsigned bits = 0; bits < choice.combinations; ++bits) {
    std::array<double, kMaxActuators> end_try = goal.end_values;
    std::array<double, kMaxActuators> middle_try = goal.middle_values;
    for (int j = 0; j < count_; ++j) {
      if ((bits >> j) & 1u) end_try[j] += settings_.step, middle_try[j] += 0.5 * settings_.step;
    }
    Pose end_pose;
    Pose middle_pose;
    probe_tracker_.reset(anchor);
    statistics_.fk_solves += 2;
    if (!probe_tracker_.solve(end_try.data(), end_pose)) return fail(period, "end");
    probe_tracker_.reset(anchor);
    if (!probe_tracker_.solve(middle_try.data(), middle_pose)) return fail(period, "middle");
    int end_hint = end_hint_;
    int mid_hint = middle_hint_;
    const double end_error = gauge_.measure(end_pose, goal.s_end, end_hint).distance_mm;
    const double middle_error = gauge_.measure(middle_pose, goal.s_middle, mid_hint).distance_mm;
    const Eigen::Vector3d try_angles =
        angles_from_rotation(machine_.mechanism->convention(), end_pose.rotation);
    choice.consider(settings_, bits, end_error, middle_error,
                    (try_angles - goal.required_angles).squaredNorm());
    if (bits == 0) end_tracker_.reset(end_pose);
  }
  return ok_status();
}

void DiscretenessCorrector::issue(const CarrierPeriod& period, const PeriodGoal& goal, unsigned chosen,
                                  StepPeriod& out) {
  out.index = period.index;
  out.time_s = period.time_s;
  for (int j = 0; j < count_; ++j) {
    const std::int64_t next = goal.floor_position[j] + ((chosen >> j) & 1u);
    out.steps[j] = static_cast<std::int32_t>(next - position_[j]);
    position_[j] = next;
    out.position[j] = next;
  }
  ++statistics_.periods;
}

Status DiscretenessCorrector::quantize(const CarrierPeriod& period, StepPeriod& out) {
  const PeriodGoal goal = period_goal(period);
  Choice choice(count_);
  Linearisation end;
  if (settings_.linearise) {
    if (!linearise(end_tracker_, goal.end_values, end)) return fail(period, "end");
    choose_linearised(goal, end, choice);
  } else if (Status chosen = choose_exact(period, goal, choice); !chosen) {
    return chosen;
  }
  unsigned chosen = choice.best_oriented < choice.combinations ? choice.best_oriented : choice.best_feasible;
  if (chosen >= choice.combinations) {
    chosen = choice.best_any, choice.chosen_end_error = choice.any_end_error,
    choice.chosen_middle_error = choice.any_middle_error;
    ++statistics_.fallbacks;
  }
  statistics_.max_predicted_error_mm =
      std::max({statistics_.max_predicted_error_mm, choice.chosen_end_error, choice.chosen_middle_error});
  if (settings_.linearise) {
    issued_point_mm_ = end.point_mm;
    for (int j = 0; j < count_; ++j) {
      if ((chosen >> j) & 1u) issued_point_mm_ += end.point_per_step[j];
    }
  }
  issue(period, goal, chosen, out);
  return ok_status();
}

}  // namespace pkm::interpolation
