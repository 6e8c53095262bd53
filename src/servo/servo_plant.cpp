#include "servo/servo_plant.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "dynamics/rigid_dynamics.hpp"
#include "dynamics/run_dynamics.hpp"
#include "servo/loop_design.hpp"

namespace pkm::servo {

Result<DriveMatrix> machine_inertia(const Machine& machine, const Pose& pose) {
  DriveMatrix out = DriveMatrix::Zero();
  if (!machine.dynamics.given()) return out;
  const Mechanism& mechanism = *machine.mechanism;
  const int m = mechanism.actuator_count();
  auto jacobian = mechanism.jacobian(pose);
  if (!jacobian) return jacobian.error();
  TwistBasis twists;
  if (!mechanism.controlled_twists(pose, twists) || jacobian->rows() != jacobian->cols())
    return make_error(ErrorCode::singular, "the drives' inertia cannot be formed at this pose");
  const Eigen::PartialPivLU<JacobianMatrix> lu(*jacobian);
  dynamics::PlatformMotion motion;
  motion.pose = pose;
  auto at_rest = dynamics::inverse_dynamics(mechanism, machine.dynamics, motion);
  if (!at_rest) return at_rest.error();
  for (int k = 0; k < m; ++k) {
    // At rest the twist rate is T c̈ with J c̈ = q̈: actuator k alone accelerating at one unit per s².
    ActuatorVector unit = ActuatorVector::Zero(m);
    unit[k] = 1.0;
    const ActuatorVector coordinate_rates = lu.solve(unit);
    const Eigen::Matrix<double, 6, 1> twist_rate = twists * coordinate_rates;
    motion.acceleration_mm_s2 = twist_rate.head<3>();
    motion.angular_acceleration_rad_s2 = twist_rate.tail<3>();
    auto forces = dynamics::inverse_dynamics(mechanism, machine.dynamics, motion);
    if (!forces) return forces.error();
    out.col(k).head(m) = forces->total - at_rest->total;
  }
  const DriveMatrix symmetric = 0.5 * (out + out.transpose());
  return symmetric;
}

DriveVector coupling_ratios(const DriveMatrix& machine_inertia, const ActuatorVector& motor_inertia,
                            int drives) {
  DriveVector out = DriveVector::Zero();
  for (int i = 0; i < drives; ++i) {
    const double sum = machine_inertia.row(i).head(drives).cwiseAbs().sum();
    out[i] = motor_inertia[i] > 0.0 ? sum / motor_inertia[i] : std::numeric_limits<double>::infinity();
  }
  return out;
}

namespace {

Error servo_plant_error_at(const ServoRunInput& input, std::size_t tick, const Error& error) {
  Error out = error;
  out.message =
      fmt::format("program line {} (t = {:.4f} s): {}", input.line[tick], input.time_s[tick], error.message);
  return out;
}

}  // namespace

Result<ServoPlant> plant_along_run(const Machine& machine, const ServoRunInput& input, int stride) {
  ServoPlant plant;
  plant.stride = std::max(1, stride);
  plant.has_machine_dynamics = machine.dynamics.given();
  const int m = machine.mechanism->actuator_count();
  const std::size_t ticks = input.time_s.size();
  const ActuatorVector motors = motor_inertia(machine.servo, m);
  DriveMatrix motor_matrix = DriveMatrix::Zero();
  motor_matrix.diagonal().head(m) = motors;
  for (std::size_t k = 0; k < ticks; k += static_cast<std::size_t>(plant.stride)) {
    auto own = machine_inertia(machine, input.pose[k]);
    if (!own) return servo_plant_error_at(input, k, own.error());
    plant.machine_inertia.push_back(*own);
    plant.inertia.push_back(*own + motor_matrix);
  }
  plant.load.assign(ticks, DriveVector::Zero());
  if (!plant.has_machine_dynamics || ticks < 3) return plant;

  // The planned forces at every tick (rigid inverse dynamics by central differences, as pkm plan --dynamics),
  // less the inertia's share A' q̈ of the set points.
  std::size_t handed = 0;
  dynamics::RunDynamics forces(machine, input.period_s, [&](const dynamics::TickDynamics& tick) -> Status {
    if (handed < ticks) plant.load[handed].head(m) = tick.forces.total;
    ++handed;
    return ok_status();
  });
  for (std::size_t k = 0; k < ticks; ++k) {
    if (Status added = forces.add(input.time_s[k], input.line[k], input.pose[k]); !added)
      return servo_plant_error_at(input, k, added.error());
  }
  if (Status finished = forces.finish(); !finished) return finished.error();
  const double h = input.period_s;
  for (std::size_t k = 1; k + 1 < ticks; ++k) {
    const ActuatorVector acceleration =
        (input.setpoint[k + 1] - 2.0 * input.setpoint[k] + input.setpoint[k - 1]) / (h * h);
    const DriveMatrix& own = plant.machine_inertia[k / static_cast<std::size_t>(plant.stride)];
    plant.load[k].head(m) -= own.topLeftCorner(m, m) * acceleration;
  }
  return plant;
}

}  // namespace pkm::servo
