#include "redundancy/law.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "dynamics/rigid_dynamics.hpp"
#include "statics/actuator_forces.hpp"
#include "statics/gravity.hpp"

namespace pkm::redundancy {

std::optional<Law> law_from_string(std::string_view name) {
  if (name == "increment") return Law::increment;
  if (name == "force") return Law::force;
  if (name == "energy") return Law::energy;
  if (name == "rotation") return Law::rotation;
  if (name == "potential") return Law::potential;
  return std::nullopt;
}

std::string_view to_string(Law law) {
  switch (law) {
    case Law::increment:
      return "increment";
    case Law::force:
      return "force";
    case Law::energy:
      return "energy";
    case Law::rotation:
      return "rotation";
    case Law::potential:
      return "potential";
  }
  return "increment";
}

bool is_pointwise(Law law) {
  return law == Law::force || law == Law::potential;
}

std::optional<EnergyAccounting> energy_accounting_from_string(std::string_view name) {
  if (name == "no-recovery") return EnergyAccounting::no_recovery;
  if (name == "braking-free") return EnergyAccounting::braking_free;
  if (name == "recovery") return EnergyAccounting::recovery;
  return std::nullopt;
}

std::string_view to_string(EnergyAccounting accounting) {
  switch (accounting) {
    case EnergyAccounting::no_recovery:
      return "no-recovery";
    case EnergyAccounting::braking_free:
      return "braking-free";
    case EnergyAccounting::recovery:
      return "recovery";
  }
  return "no-recovery";
}

std::optional<ForceModel> force_model_from_string(std::string_view name) {
  if (name == "statics") return ForceModel::statics;
  if (name == "dynamics") return ForceModel::dynamics;
  return std::nullopt;
}

std::string_view to_string(ForceModel model) {
  return model == ForceModel::dynamics ? "dynamics" : "statics";
}

LawEvaluator::LawEvaluator(const Machine& machine, const FreeCoordinates& free, const LawOptions& options,
                           bool need_forces)
    : machine_(machine),
      free_(free),
      options_(options),
      need_forces_(need_forces || options.law == Law::force || options.law == Law::energy ||
                   options.force_limit_N.has_value()),
      characteristic_length_mm_(machine.mechanism->platform_size_mm()) {
  const Mechanism& mechanism = *machine.mechanism;
  JacobianMatrix twist;
  six_axis_twist_ = mechanism.controlled_axes().count() == 6 && mechanism.actuator_count() == 6 &&
                    mechanism.twist_jacobian(mechanism.home(), twist);
}

double LawEvaluator::normalized_determinant(const Pose& pose) const noexcept {
  JacobianMatrix jacobian;
  if (six_axis_twist_) {
    if (!machine_.mechanism->twist_jacobian(pose, jacobian)) return std::numeric_limits<double>::quiet_NaN();
  } else {
    auto computed = machine_.mechanism->jacobian(pose);
    if (!computed || computed->rows() != computed->cols()) return std::numeric_limits<double>::quiet_NaN();
    jacobian = *computed;
  }
  // Angle columns (rad) to lengths: a turn by one radian moves the joints by about the characteristic length.
  const AxisMask axes = machine_.mechanism->controlled_axes();
  int column = 0;
  for (int axis = 0; axis < 6; ++axis) {
    if (!six_axis_twist_ && !axes.controlled[axis]) continue;
    if (axis >= 3) jacobian.col(column) /= characteristic_length_mm_;
    ++column;
  }
  double rows = 1.0;
  for (int r = 0; r < jacobian.rows(); ++r) rows *= jacobian.row(r).norm();
  if (!(rows > 0.0)) return 0.0;
  return jacobian.partialPivLu().determinant() / rows;
}

int LawEvaluator::branch_sign(const Pose& pose) const noexcept {
  const double value = normalized_determinant(pose);
  if (!std::isfinite(value) || value == 0.0 || std::abs(value) < min_determinant_) return 0;
  return value > 0.0 ? 1 : -1;
}

bool LawEvaluator::set_start(const Pose& start) {
  const double value = normalized_determinant(start);
  if (!std::isfinite(value) || std::abs(value) < 1e-9) return false;
  branch_sign_ = value > 0.0 ? 1 : -1;
  min_determinant_ = options_.singularity_margin * std::abs(value);
  return true;
}

bool LawEvaluator::evaluate(const PathPoint& point, const statics::Wrench& load, const FreeValues& values,
                            Node& node, bool check_branch) const noexcept {
  node.valid = false;
  const Pose pose = free_.pose(point, values);
  node.pose = pose;
  const int n = machine_.mechanism->actuator_count();
  node.lengths.resize(n);
  if (!machine_.mechanism->actuator_values(pose, node.lengths.data())) return false;
  const ActuatorLimits& limits = machine_.limits;
  for (int j = 0; j < n; ++j) {
    const double q = node.lengths[j];
    if (!std::isfinite(q) || (limits.min && q < *limits.min) || (limits.max && q > *limits.max)) return false;
  }
  if (check_branch && branch_sign_ != 0 && branch_sign(pose) != branch_sign_) return false;
  node.forces.setZero(n);
  if (need_forces_ && options_.forces == ForceModel::dynamics) {
    // The static part of the rigid dynamics (every body's weight and the load); the step adds the motion.
    auto complete = machine_.mechanism->complete_pose(pose);
    if (!complete) return false;
    node.pose = *complete;
    node.load = load;
    node.step_s = point.feed_mm_s > 0.0 && point.step_mm > 0.0 ? point.step_mm / point.feed_mm_s : 0.0;
    dynamics::PlatformMotion rest;
    rest.pose = node.pose;
    auto forces = dynamics::inverse_dynamics(*machine_.mechanism, machine_.dynamics, rest, load);
    if (!forces) return false;
    node.forces = forces->total;
  } else if (need_forces_) {
    statics::Wrench wrench = load;
    if (machine_.masses.has_mass()) {
      // The weight of the moving parts is a load like the cut (Smirnov 2019, ch. 3).
      StrutJointPoints struts;
      const int strut_count = machine_.mechanism->strut_joints(pose, struts);
      const statics::Wrench weight = statics::gravity_wrench(
          machine_.masses, pose, strut_count > 0 ? &struts : nullptr, std::max(0, strut_count));
      wrench.force_N += weight.force_N;
      wrench.moment_Nmm += weight.moment_Nmm;
    }
    if (six_axis_twist_) {
      if (!statics::twist_actuator_forces(*machine_.mechanism, pose, wrench, node.forces.data()))
        return false;
    } else {
      auto forces = statics::actuator_forces(*machine_.mechanism, pose, wrench);
      if (!forces) return false;
      node.forces = *forces;
    }
    if (options_.force_limit_N && node.forces.cwiseAbs().maxCoeff() > *options_.force_limit_N) return false;
  }
  node.valid = true;
  return true;
}

ActuatorVector LawEvaluator::step_forces(const Node& from, const Node& to) const noexcept {
  if (options_.forces != ForceModel::dynamics || !(to.step_s > 0.0)) return to.forces;
  // The platform moving from `from` to `to` in the step's time: the twist of the step, about the tool point.
  dynamics::PlatformMotion motion;
  motion.pose = to.pose;
  motion.velocity_mm_s = (to.pose.position_mm - from.pose.position_mm) / to.step_s;
  const Eigen::AngleAxisd turn(to.pose.rotation * from.pose.rotation.transpose());
  motion.angular_velocity_rad_s = turn.angle() / to.step_s * turn.axis();
  auto forces = dynamics::inverse_dynamics(*machine_.mechanism, machine_.dynamics, motion, to.load);
  return forces ? forces->total : to.forces;
}

double LawEvaluator::step_energy_Nmm(const Node& from, const Node& to) const noexcept {
  // Forces at the end of the step: the law chooses the end pose with the loads known there (Smirnov, §3.4.3).
  const ActuatorVector forces = step_forces(from, to);
  const int n = static_cast<int>(to.lengths.size());
  double total = 0.0;
  double signed_total = 0.0;
  for (int j = 0; j < n; ++j) {
    const double work = (to.lengths[j] - from.lengths[j]) * forces[j];
    signed_total += work;
    switch (options_.energy) {
      case EnergyAccounting::no_recovery:
        total += std::abs(work);
        break;
      case EnergyAccounting::braking_free:
        total += std::max(0.0, work);
        break;
      case EnergyAccounting::recovery:
        break;
    }
  }
  return options_.energy == EnergyAccounting::recovery ? std::abs(signed_total) : total;
}

double LawEvaluator::step_cost(const Node& from, const Node& to) const noexcept {
  switch (options_.law) {
    case Law::increment:
      return (to.lengths - from.lengths).cwiseAbs().maxCoeff();
    case Law::force:
      return to.forces.cwiseAbs().maxCoeff();
    case Law::energy:
      return step_energy_Nmm(from, to);
    case Law::rotation:
      return Eigen::AngleAxisd(from.pose.rotation.transpose() * to.pose.rotation).angle();
    case Law::potential:
      return limit_potential(to);
  }
  return 0.0;
}

// The largest V(u) = 1/u + 1/(1 − u) − 4 over the actuators, u an actuator's place in [actuator_min,
// actuator_max]: 0 mid-range, +∞ at a limit (the barrier of the virtual-potential scenario; optimize_program
// checks that both limits are given). The largest, not the sum: the actuator nearest its limit decides, as
// the largest force does in the force law, so the law keeps the smallest margin as large as it can be.
double LawEvaluator::limit_potential(const Node& node) const noexcept {
  const ActuatorLimits& limits = machine_.limits;
  if (!limits.min || !limits.max || !(*limits.max > *limits.min)) return 0.0;
  const double range = *limits.max - *limits.min;
  double largest = 0.0;
  for (Eigen::Index j = 0; j < node.lengths.size(); ++j) {
    const double u = (node.lengths[j] - *limits.min) / range;
    if (!(u > 0.0 && u < 1.0)) return std::numeric_limits<double>::infinity();
    largest = std::max(largest, 1.0 / u + 1.0 / (1.0 - u) - 4.0);
  }
  return largest;
}

}  // namespace pkm::redundancy
