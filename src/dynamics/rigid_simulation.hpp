#pragma once
// Forward dynamics of the rigid machine (Smirnov 2019, §4.2): the drives push the struts with forces P_j(t)
// and the platform, a free platform of free_platform.hpp, moves as
//   M(pose) c̈ = applied(pose) − bias(pose, ċ) + J_Bᵀ P · 10³          (kg·mm/s², P in N)
// (equations_of_motion.hpp with the drives' forces; the inverse problem is rigid_dynamics.hpp). The drive
// turns its command u_j (N) into its force by the machine file's drive model (drive_model.hpp). Integrated by
// platform_integrator.hpp. Commanding the inverse dynamics' forces along a planned motion (feed-forward
// without feedback) reproduces that motion with ideal drives; what a lag or a speed-dependent force makes of
// it is the motion's open-loop error (docs/dynamics.md): there is no feedback here, so the error grows
// without bound where the command is wrong (a servo closes the loop).
#include <memory>
#include <vector>

#include "dynamics/drive_model.hpp"
#include "dynamics/platform_integrator.hpp"

namespace pkm::dynamics {

/// The drives' commands u_j(t), N. Called from inside the integrator's steps at any time within the interval
/// being advanced over; must not allocate.
class DriveCommand {
 public:
  virtual ~DriveCommand() = default;
  virtual void command_N(double time_s, ActuatorVector& out) const = 0;
};

/// A command known at sample times, linear between them and held beyond the ends (the feed-forward forces of
/// a planned run, one sample per servo tick).
class SampledDriveCommand final : public DriveCommand {
 public:
  /// `times_s` ascending, one force vector per time (all of the same size).
  SampledDriveCommand(std::vector<double> times_s, std::vector<ActuatorVector> forces_N);
  void command_N(double time_s, ActuatorVector& out) const override;

 private:
  std::vector<double> times_s_;
  std::vector<ActuatorVector> forces_N_;
};

class RigidSimulator {
 public:
  /// The model (and the machine it refers to) must outlive the simulator. A constant external `load` on the
  /// platform (N, N·mm about the tool point) may be given.
  RigidSimulator(const FreePlatformModel& model, const PlatformIntegration& integration = {},
                 const statics::Wrench& load = {});
  ~RigidSimulator();
  RigidSimulator(RigidSimulator&&) noexcept;
  RigidSimulator& operator=(RigidSimulator&&) noexcept;

  /// Starts at `time_s` from a pose moving with coordinate rates `rates`; a lagging drive starts with the
  /// force `initial_force_N` (ignored by the other models). τ of the rates' scaling is the integration's
  /// rate_time_scale_s, or else the drive's lag, or else 10 ms. Fails where the pose is out of reach.
  Status start(double time_s, const Pose& pose, const CoordinateVector& rates,
               const ActuatorVector& initial_force_N);
  /// Integrates to `time_s` under `command` (see PlatformIntegrator::advance_to). Fails where the platform
  /// leaves the mechanism's reach, crosses a singular position, or the step size collapses.
  Status advance_to(double time_s, const DriveCommand& command);

  double time_s() const;
  Pose pose() const;
  CoordinateVector rates() const;
  /// The drives' forces now, N (the lag's state, or the model's force for the command at this time).
  ActuatorVector drive_force_N(const DriveCommand& command) const;
  const IntegrationCounters& counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::dynamics
