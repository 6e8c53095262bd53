#include "interpolation/methods/estimating_function.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pkm::interpolation {

namespace {
/// Progress and angle differences below these count as ties (round-off of FK at 1e-10 mm and of the
/// projection).
constexpr double kEstimatingProgressTie = 1e-12;
constexpr double kEstimatingAngleTie = 1e-12;
/// A value within this many steps of a whole step counts as that step when rounding (FK/IK round-off).
constexpr double kEstimatingStepRoundOff = 1e-9;

std::int64_t estimating_truncate(double steps) {
  return static_cast<std::int64_t>(std::trunc(steps + std::copysign(kEstimatingStepRoundOff, steps)));
}
}  // namespace

EstimatingInterpolator::EstimatingInterpolator(const Machine& machine, const path::Path& path,
                                               const EstimatingSettings& settings, std::string source)
    : machine_(machine),
      path_(path),
      settings_(settings),
      source_(std::move(source)),
      workspace_(machine.mechanism->make_fk_workspace()),
      actuators_(machine.mechanism->actuator_count()),
      projector_(path, machine.mechanism->controlled_axes()) {
  const AxisMask axes = machine.mechanism->controlled_axes();
  // Orientation is compared only where the mechanism sets all of it (or the planar φ alone).
  controls_orientation_ = axes.controlled[5] && axes.controlled[3] == axes.controlled[4];
}

bool EstimatingInterpolator::fail(ErrorCode code, const std::string& message, double s) {
  error_ = make_error(code, fmt::format("{}:{}: {}", source_, projector_.line_at(s), message));
  return false;
}

Status EstimatingInterpolator::start() {
  started_ = finished_ = false;
  error_.reset();
  statistics_ = {};
  stall_tacts_ = 0;
  const double step = settings_.step_mm;
  if (!(step > 0.0) || !(settings_.deviation_mm > 0.0) || settings_.max_stall_tacts < 0) {
    fail(ErrorCode::bad_input,
         fmt::format("estimating-function interpolation needs a positive step ({}), deviation limit ({}) and "
                     "max_stall_tacts ({})",
                     step, settings_.deviation_mm, settings_.max_stall_tacts),
         0.0);
    return *error_;
  }
  auto directions = candidate_directions(settings_.candidates, actuators_, settings_.struts_per_tact);
  if (!directions) {
    fail(directions.error().code, directions.error().message, 0.0);
    return *error_;
  }
  directions_ = std::move(directions.value());
  // Progress is measured on the path parameter, which counts degrees where only the orientation moves: the
  // method's criteria (§5.2.1) are about the tool point's position, so such moves have no progress to make.
  for (const path::Segment& segment : path_.segments) {
    if (segment.rotation_only) {
      error_ = make_error(ErrorCode::unsupported,
                          fmt::format("{}:{}: the estimating-function interpolator follows the tool point's "
                                      "path; a move that only rotates the platform has none",
                                      source_, segment.line));
      return *error_;
    }
  }
  // The final rule (§5.2.1, step 3) is progress ≥ Δ; the first one (Fig. 147) only forbids moving back.
  min_progress_mm_ = settings_.progress_at_least_step ? step : 0.0;

  // Start: the start pose's actuator values, truncated to whole steps (Smirnov 2019, §5.2.5).
  Pose start_pose;
  start_pose.position_mm = path_.start.position_mm;
  start_pose.rotation = path_.start.rotation.toRotationMatrix();
  auto ideal = machine_.mechanism->inverse(start_pose);
  if (!ideal) {
    fail(ideal.error().code, "the path's start is out of reach: " + ideal.error().message, 0.0);
    return *error_;
  }
  ActuatorVector actuators(actuators_);
  for (int j = 0; j < actuators_; ++j) {
    steps_[j] = estimating_truncate((*ideal)[j] / step);
    actuators[j] = static_cast<double>(steps_[j]) * step;
    min_steps_[j] =
        machine_.limits.min
            ? static_cast<std::int64_t>(std::ceil(*machine_.limits.min / step - kEstimatingStepRoundOff))
            : std::numeric_limits<std::int64_t>::min();
    max_steps_[j] =
        machine_.limits.max
            ? static_cast<std::int64_t>(std::floor(*machine_.limits.max / step + kEstimatingStepRoundOff))
            : std::numeric_limits<std::int64_t>::max();
  }
  if (Status range = check_actuator_range(machine_, actuators); !range) {
    fail(range.error().code, "the path's start is out of reach: " + range.error().message, 0.0);
    return *error_;
  }
  for (int j = 0; j < actuators_; ++j) {
    if (steps_[j] < min_steps_[j] || steps_[j] > max_steps_[j]) {
      fail(ErrorCode::limit_exceeded,
           fmt::format("the path's start is out of reach: actuator {} at {} whole steps of {} is outside its "
                       "range",
                       j + 1, steps_[j], step),
           0.0);
      return *error_;
    }
  }
  workspace_->reset();
  pose_ = start_pose;
  if (!solve(actuators, pose_)) {
    fail(ErrorCode::not_converged,
         "forward kinematics of the start's whole-step actuator values failed (singular start?)", 0.0);
    return *error_;
  }
  projector_.anchor(0.0);
  const EstimatingNearest nearest = projector_.nearest(pose_.position_mm);
  s_ = s_start_ = s_best_ = nearest.s;
  statistics_.start_error_mm = nearest.distance_mm;
  end_distance_mm_ = projector_.distance_to_end_mm(pose_.position_mm);
  started_ = true;
  return ok_status();
}

bool EstimatingInterpolator::solve(const ActuatorVector& actuators, Pose& pose) {
  ++statistics_.fk_solves;
  // Every candidate starts from the current pose with the workspace's factorisation from the previous solve
  // (on a hexapod a pose a few steps away serves as a chord-Newton matrix). Forgetting the solution history
  // keeps the workspace from extrapolating a "path" through the previous tact's candidates.
  workspace_->forget_path();
  auto solution = machine_.mechanism->forward_warm(actuators, pose_, settings_.fk, *workspace_);
  if (!solution) return false;
  pose = solution->pose;
  return true;
}

double EstimatingInterpolator::rotation_deviation(const Pose& pose, const EstimatingNearest& nearest) const {
  if (!controls_orientation_) return 0.0;
  return Eigen::Quaterniond(pose.rotation).angularDistance(nearest.rotation);
}

void EstimatingInterpolator::apply(const Candidate& chosen, bool fallback, bool end_approach, Tact& tact) {
  const StepDirections& d = directions_[chosen.index];
  tact = Tact{};
  for (int j = 0; j < actuators_; ++j) {
    steps_[j] += d[j];
    tact.direction[j] = d[j];
    tact.moved += d[j] != 0 ? 1 : 0;
  }
  pose_ = chosen.pose;
  s_ = chosen.nearest.s;
  end_distance_mm_ = chosen.end_distance_mm;
  tact.s = s_;
  tact.deviation_mm = chosen.nearest.distance_mm;
  tact.fallback = fallback;
  tact.progress_mm = chosen.progress_mm;
  tact.rotation_deviation_rad = rotation_deviation(chosen.pose, chosen.nearest);
  tact.end_approach = end_approach;
  ++statistics_.tacts;
  if (fallback) ++statistics_.fallbacks;
  if (tact.deviation_mm > statistics_.max_deviation_mm) {
    statistics_.max_deviation_mm = tact.deviation_mm;
    statistics_.max_deviation_line = projector_.line_at(s_);
  }
  statistics_.max_rotation_deviation_rad =
      std::max(statistics_.max_rotation_deviation_rad, tact.rotation_deviation_rad);
}

bool EstimatingInterpolator::evaluate(int c, ActuatorVector& actuators, Candidate& candidate) {
  ++statistics_.candidates;
  const StepDirections& d = directions_[c];
  bool in_range = true;
  for (int j = 0; j < actuators_; ++j) {
    const std::int64_t q = steps_[j] + d[j];
    in_range = in_range && q >= min_steps_[j] && q <= max_steps_[j];
    actuators[j] = static_cast<double>(q) * settings_.step_mm;
  }
  if (!in_range) {
    ++statistics_.out_of_range;
    return false;
  }
  if (!solve(actuators, candidate.pose)) {
    ++statistics_.fk_failures;
    return false;
  }
  candidate.index = c;
  candidate.nearest = projector_.nearest(candidate.pose.position_mm);
  candidate.progress_mm = candidate.nearest.s - s_;
  candidate.end_distance_mm = projector_.distance_to_end_mm(candidate.pose.position_mm);
  return true;
}

void EstimatingInterpolator::rank(Candidate& candidate, bool end_zone, Candidates& best) {
  const double deviation = candidate.nearest.distance_mm;
  const double deviation_limit = settings_.deviation_mm;
  if (end_zone) {
    if (!best.end_any.found() || candidate.end_distance_mm < best.end_any.end_distance_mm)
      best.end_any = candidate;
    if (deviation <= deviation_limit &&
        (!best.end_within.found() || candidate.end_distance_mm < best.end_within.end_distance_mm)) {
      best.end_within = candidate;
    }
    return;
  }
  Candidate& admissible = best.admissible;
  const bool progresses = settings_.progress_at_least_step ? candidate.progress_mm >= min_progress_mm_
                                                           : candidate.progress_mm > 0.0;
  if (deviation <= deviation_limit && progresses) {
    if (settings_.minimise_orientation) {
      // eq. 143: the least orientation deviation from the path's, ties to the larger progress.
      candidate.rotation_rad = rotation_deviation(candidate.pose, candidate.nearest);
      const bool better = !admissible.found() ||
                          candidate.rotation_rad < admissible.rotation_rad - kEstimatingAngleTie ||
                          (candidate.rotation_rad <= admissible.rotation_rad + kEstimatingAngleTie &&
                           candidate.progress_mm > admissible.progress_mm);
      if (better) admissible = candidate;
    } else {
      // §5.2.1, step 4: the largest progress (fewest tacts), ties to the smaller deviation.
      const bool better = !admissible.found() ||
                          candidate.progress_mm > admissible.progress_mm + kEstimatingProgressTie ||
                          (candidate.progress_mm >= admissible.progress_mm - kEstimatingProgressTie &&
                           deviation < admissible.nearest.distance_mm);
      if (better) admissible = candidate;
    }
  }
  if (candidate.progress_mm > 0.0 &&
      (!best.advancing.found() || deviation < best.advancing.nearest.distance_mm)) {
    best.advancing = candidate;
  }
  if (!best.closest.found() || deviation < best.closest.nearest.distance_mm) best.closest = candidate;
}

bool EstimatingInterpolator::finish_end_zone(const Candidates& best, Tact& tact) {
  const Candidate& nearest_end = best.end_within.found() ? best.end_within : best.end_any;
  if (!nearest_end.found() || nearest_end.end_distance_mm >= end_distance_mm_) {
    // No step brings the tool closer to the end point: the path is done.
    finished_ = true;
    statistics_.end_error_mm = end_distance_mm_;
    return false;
  }
  apply(nearest_end, !best.end_within.found(), true, tact);
  return true;
}

bool EstimatingInterpolator::take_best(const Candidates& best, Tact& tact) {
  if (best.admissible.found()) {
    // Stall detection counts tacts that do not carry the tool beyond the farthest point already reached.
    if (best.admissible.nearest.s > s_best_) {
      s_best_ = best.admissible.nearest.s;
      stall_tacts_ = 0;
    } else if (++stall_tacts_ > settings_.max_stall_tacts) {
      return fail(ErrorCode::not_converged,
                  fmt::format("estimating-function interpolation circles at s = {:.6f} mm: {} tacts in a row "
                              "without getting farther along the path than before (max_stall_tacts = {})",
                              s_, stall_tacts_, settings_.max_stall_tacts),
                  s_);
    }
    apply(best.admissible, false, false, tact);
    return true;
  }
  const Candidate& fallback = best.advancing.found() ? best.advancing : best.closest;
  if (!fallback.found()) {
    return fail(ErrorCode::singular,
                fmt::format("no candidate move from s = {:.6f} mm has a forward-kinematics solution in this "
                            "assembly mode within the actuator limits",
                            s_),
                s_);
  }
  if (++stall_tacts_ > settings_.max_stall_tacts) {
    const Eigen::Vector3d& p = pose_.position_mm;
    const std::string required =
        settings_.progress_at_least_step
            ? fmt::format("advances along the path by at least Δ = {} mm", settings_.step_mm)
            : std::string("advances along the path");
    return fail(ErrorCode::not_converged,
                fmt::format("estimating-function interpolation stalled at s = {:.6f} mm, tool point ({:.6f}, "
                            "{:.6f}, {:.6f}) mm: no candidate within δ = {} mm {} ({} tacts in a row without "
                            "admissible progress, max_stall_tacts = {}); allow a larger deviation or use a "
                            "finer step",
                            s_, p.x(), p.y(), p.z(), settings_.deviation_mm, required, stall_tacts_,
                            settings_.max_stall_tacts),
                s_);
  }
  apply(fallback, true, false, tact);
  return true;
}

bool EstimatingInterpolator::next(Tact& tact) {
  if (!started_ || finished_ || error_) return false;
  const double remaining_mm = path_.length() - s_;
  // Typical progress per tact: the run's mean so far, at least one step (the final rule of §5.2.1).
  const double typical_mm =
      std::max(settings_.step_mm,
               statistics_.tacts > 0 ? (s_ - s_start_) / static_cast<double>(statistics_.tacts) : 0.0);
  const bool end_zone = remaining_mm <= typical_mm;
  projector_.anchor(s_);
  Candidates best;
  Candidate candidate;
  ActuatorVector actuators(actuators_);
  const int count = static_cast<int>(directions_.size());
  for (int c = 0; c < count; ++c) {
    if (evaluate(c, actuators, candidate)) rank(candidate, end_zone, best);
  }
  return end_zone ? finish_end_zone(best, tact) : take_best(best, tact);
}

}  // namespace pkm::interpolation
