#pragma once
// What the drives move along a run (motion-control textbook, §2.7.1): the inertia matrix in actuator
// coordinates, A = A'(q) + diag(J_m,i), and the load d each drive carries besides the inertia.
//   A'(q): the machine's own inertia (the dynamics: section's bodies), from the rigid-body inverse dynamics
//     at rest: column k is the drive forces for a unit acceleration of actuator k alone (eq. 2.44's kinetic
//     energy form, a_ik, through the Mechanism interface);
//   J_m,i: the motor's inertia reflected onto its coordinate (loop_design.hpp);
//   d: the planned forces less A' q̈ of the set points, i.e. gravity, the process load and the velocity
//     terms, which §2.7.1 lumps into the disturbance Q_b.
// The coupling check of §2.7.1: each coordinate may be controlled as an independent channel where
// Σ_k |A'_ik| / J_m,i < 0.3 (ε Σ_k J'_ik/J_ii with the gear's ε = 1/i² moved onto the actuator side).
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "servo/servo_simulator.hpp"

namespace pkm::servo {

/// The machine's inertia on the actuator coordinates at the complete, reachable `pose`, symmetric, in
/// N/(mm/s²) (N·mm/(rad/s²)); zero where the machine file has no dynamics: section.
Result<DriveMatrix> machine_inertia(const Machine& machine, const Pose& pose);

/// The coupling ratio of each drive, Σ_k |A'_ik| / J_m,i (∞ where the motor's inertia is not given).
DriveVector coupling_ratios(const DriveMatrix& machine_inertia, const ActuatorVector& motor_inertia,
                            int drives);

/// The run's set points and commanded poses, one per servo tick.
struct ServoRunInput {
  double period_s = 0.0;  ///< the servo (CNC) period
  std::vector<double> time_s;
  std::vector<int> line;
  std::vector<ActuatorVector> setpoint;  ///< mm (rad)
  std::vector<Pose> pose;                ///< the commanded tool pose, complete, base frame
};

/// The plant along a run: inertia samples every `stride` ticks (held until the next), the load every tick.
struct ServoPlant {
  int stride = 1;
  std::vector<DriveMatrix> inertia;          ///< A = A' + motors, sample i from tick i·stride
  std::vector<DriveMatrix> machine_inertia;  ///< A' alone
  std::vector<DriveVector> load;             ///< d per tick
  bool has_machine_dynamics = false;         ///< A' and d came from a dynamics: section
};

/// Evaluates the plant along `input` (the dynamics: section's bodies, the motors of `servo:`). Fails, at the
/// program line, where a pose is out of reach or singular, or the planned forces exceed the drives' limit.
Result<ServoPlant> plant_along_run(const Machine& machine, const ServoRunInput& input, int stride);

}  // namespace pkm::servo
