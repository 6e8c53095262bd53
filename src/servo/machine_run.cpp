#include "servo/machine_run.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <cmath>
#include <limits>

#include "servo/servo_simulator.hpp"

namespace pkm::servo {

namespace {

Error machine_run_error(const ServoRunInput& input, std::size_t k, const std::string& what) {
  return make_error(ErrorCode::not_converged,
                    fmt::format("program line {} (t = {:.4f} s): {}", input.line[k], input.time_s[k], what));
}

// The contour error vectors of actual tool points against the commanded path.
class ContourVectors {
 public:
  explicit ContourVectors(const MachineRunInputs& inputs)
      : path_(*inputs.path),
        axes_(inputs.machine->mechanism->controlled_axes()),
        ticks_(inputs.input->time_s.size()),
        window_(inputs.search_window) {}

  // Actual − nearest commanded point, searching the path back from tick k.
  Eigen::Vector3d at(const Eigen::Vector3d& actual_mm, std::size_t k) const {
    const Eigen::Vector3d point = controlled_point(actual_mm, axes_);
    const std::size_t first = k > window_ ? 2 * (k - window_) : 0;
    const std::size_t last = 2 * std::min(k + 1, ticks_ - 1);
    return point - nearest_on_path(path_, first, last, point).point;
  }

 private:
  const CommandedPath& path_;
  AxisMask axes_;
  std::size_t ticks_;
  std::size_t window_;
};

// The process load the drives carry on the rigid plant: the forces d that hold the wrench w statically,
// J_tᵀ d = −w (virtual work with the twist Jacobian; least squares where the drives control fewer than six
// coordinates).
Result<DriveVector> load_on_drives(const Mechanism& mechanism, const Pose& pose, const statics::Wrench& w) {
  JacobianMatrix jacobian;
  if (!mechanism.twist_jacobian(pose, jacobian))
    return make_error(ErrorCode::singular, "no twist Jacobian at the commanded pose");
  Eigen::Matrix<double, 6, 1> wrench;
  wrench << w.force_N, w.moment_Nmm;
  DriveVector d = DriveVector::Zero();
  d.head(jacobian.rows()) = jacobian.transpose().completeOrthogonalDecomposition().solve(-wrench);
  return d;
}

DriveMatrix inverse_of(const DriveMatrix& inertia, int drives) {
  DriveMatrix out = DriveMatrix::Zero();
  out.topLeftCorner(drives, drives) = inertia.topLeftCorner(drives, drives).inverse();
  return out;
}

Status run_rigid(const MachineRunInputs& in, const LoopDesign& design, bool with_load,
                 const std::function<Status(const MachineRunTick&)>& on_tick) {
  const ServoRunInput& input = *in.input;
  const ServoPlant& plant = *in.plant;
  const Mechanism& mechanism = *in.machine->mechanism;
  const int m = design.drives;
  const ContourVectors contour(in);
  std::vector<DriveVector> load(input.time_s.size(), DriveVector::Zero());
  for (std::size_t k = 0; k < load.size(); ++k) {
    load[k] = plant.load[k];
    if (!with_load || !in.load) continue;
    auto process = load_on_drives(mechanism, input.pose[k], (*in.load)[k]);
    if (!process) return machine_run_error(input, k, process.error().message);
    load[k] += *process;
  }
  ServoSimulator simulator(design, input.period_s / in.steps_per_period);
  simulator.set_inverse_inertia(inverse_of(plant.inertia[0], m));
  simulator.set_load(load[0]);
  DriveVector previous = DriveVector::Zero(), setpoint = DriveVector::Zero();
  setpoint.head(m) = input.setpoint[0];
  simulator.reset(setpoint);
  auto fk_workspace = mechanism.make_fk_workspace();
  Pose guess = input.pose[0];
  ActuatorVector actuators(m);
  std::size_t sample = 0;
  for (std::size_t k = 0; k < input.time_s.size(); ++k) {
    if (k > 0) {
      previous = setpoint;
      setpoint.head(m) = input.setpoint[k];
      if (const std::size_t s = (k - 1) / static_cast<std::size_t>(plant.stride);
          s != sample && s < plant.inertia.size()) {
        sample = s;
        simulator.set_inverse_inertia(inverse_of(plant.inertia[s], m));
      }
      simulator.set_load(0.5 * (load[k - 1] + load[k]));
      const DriveVector speed = (setpoint - previous) / input.period_s;
      for (int i = 0; i < in.steps_per_period; ++i)
        simulator.step(previous + (static_cast<double>(i) / in.steps_per_period) * (setpoint - previous),
                       speed);
      if (!simulator.finite()) return machine_run_error(input, k, "the servo loops diverged");
    }
    MachineRunTick tick{k, input.time_s[k], input.line[k], input.pose[k].position_mm};
    actuators = simulator.actuator_position().head(m);
    if (auto fk = mechanism.forward_warm(actuators, guess, FkOptions{}, *fk_workspace)) {
      guess = fk->pose;
      tick.actual_mm = fk->pose.position_mm;
      tick.contour_mm = contour.at(tick.actual_mm, k);
    } else {
      tick.actual_mm = tick.contour_mm = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    }
    tick.position = &simulator.actuator_position();
    tick.force = &simulator.force();
    if (Status told = on_tick(tick); !told) return told;
  }
  return ok_status();
}

Status run_elastic(const MachineRunInputs& in, const LoopDesign& design, bool with_load,
                   const std::function<Status(const MachineRunTick&)>& on_tick) {
  const ServoRunInput& input = *in.input;
  const int m = design.drives;
  const ContourVectors contour(in);
  auto coupled = CoupledMachine::make(*in.machine, design, input.period_s / in.steps_per_period, in.coupled);
  if (!coupled) return coupled.error();
  const auto load_at = [&](std::size_t k) {
    return with_load && in.load ? (*in.load)[k] : statics::Wrench{};
  };
  DriveVector previous = DriveVector::Zero(), setpoint = DriveVector::Zero();
  setpoint.head(m) = input.setpoint[0];
  if (Status reset = coupled->reset(input.time_s[0], setpoint, input.pose[0], load_at(0)); !reset)
    return machine_run_error(input, 0, reset.error().message);
  for (std::size_t k = 0; k < input.time_s.size(); ++k) {
    if (k > 0) {
      previous = setpoint;
      setpoint.head(m) = input.setpoint[k];
      const statics::Wrench before = load_at(k - 1), after = load_at(k);
      coupled->set_load(
          {0.5 * (before.force_N + after.force_N), 0.5 * (before.moment_Nmm + after.moment_Nmm)});
      const DriveVector speed = (setpoint - previous) / input.period_s;
      for (int i = 0; i < in.steps_per_period; ++i) {
        const DriveVector reference =
            previous + (static_cast<double>(i) / in.steps_per_period) * (setpoint - previous);
        if (Status stepped = coupled->step(reference, speed); !stepped)
          return machine_run_error(input, k, stepped.error().message);
      }
      if (!coupled->position().allFinite()) return machine_run_error(input, k, "the servo loops diverged");
    }
    MachineRunTick tick{k, input.time_s[k], input.line[k], input.pose[k].position_mm};
    tick.actual_mm = coupled->pose().position_mm;
    tick.contour_mm = contour.at(tick.actual_mm, k);
    tick.position = &coupled->position();
    tick.force = &coupled->force();
    if (Status told = on_tick(tick); !told) return told;
  }
  return ok_status();
}

}  // namespace

LoopDesign ideal_drives(const LoopDesign& design) {
  LoopDesign out = design;
  out.sample_delay_periods = 0;
  for (ChannelGains& c : out.channels) {
    c.friction_coulomb = c.friction_static = c.stribeck_speed = c.friction_viscous = 0.0;
    c.backlash = c.encoder_resolution = 0.0;
    c.characteristic_points = 0;
  }
  return out;
}

Status run_machine(const MachineRunInputs& inputs, const MachineRunSetup& setup,
                   const std::function<Status(const MachineRunTick&)>& on_tick) {
  const LoopDesign design = setup.imperfections ? *inputs.design : ideal_drives(*inputs.design);
  if (inputs.input->time_s.empty()) return ok_status();
  return setup.elastic ? run_elastic(inputs, design, setup.load, on_tick)
                       : run_rigid(inputs, design, setup.load, on_tick);
}

}  // namespace pkm::servo
