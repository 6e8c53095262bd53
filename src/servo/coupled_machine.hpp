#pragma once
// The machine in the loop (docs/simulate.md): every drive's servo cascade (drive_regulators.hpp) closing its
// loops on the elastic machine (dynamics/elastic_model.hpp, Smirnov 2019 §4.5) instead of on a rigid plant.
// Each drive is a mass m_j (its motor's inertia on the actuator coordinate, J_m · (2π/lead)²) that its
// current loop pushes with the force F_j, and that pushes the strut through the elastic element in series
// with it (the strut's stiffness and the transmission's, in series; with the transmission's lost motion):
//   m_j q̈_j = F_j − f_j(q̇_j) + T_j,        T_μ,j Ḟ_j + F_j = F_cmd,j   (held over each loop period)
//   M(pose) c̈ = applied(pose) + load − bias(pose, ċ) − J_Bᵀ T · 10³           (elastic_model.hpp)
// with T_j = c_j (a_j − q_j) + D_j(ȧ_j − q̇_j) the element's tension and f_j the drive's friction
// (Coulomb + Stribeck + viscous, its sign smoothed over v_ε: a continuous integrator cannot stick, so below
// v_ε the friction acts as a steep viscous one). The regulators sample the motors' q and q̇ every loop period
// (through the encoder and the sampling delay), and Dormand–Prince 5(4) (platform_integrator.hpp) integrates
// the platform and the drives between the samples, stopping on each so that the held command changes there.
//
// Power balance (tested to 10⁻⁶): Σ F_j q̇_j + load · twist = d/dt (T + ½ Σ m q̇² + Π + V) + Σ f_j q̇_j
// + Σ D_j (ȧ_j − q̇_j); with `track_energy` the two integrals on its left and its dissipation are integrated
// with the state.
#include <memory>

#include "core/result.hpp"
#include "dynamics/elastic_model.hpp"
#include "dynamics/platform_integrator.hpp"
#include "servo/drive_regulators.hpp"

namespace pkm::servo {

struct CoupledOptions {
  /// Tolerances of the integration (platform_integrator.hpp); τ 0: 1/ω of the fastest mode at the start.
  dynamics::PlatformIntegration integration = {1e-6, 1e-8, 0.0, 0.0, 5'000'000};
  /// The speed over which the sign of the drives' dry friction is smoothed (tanh), mm/s.
  double friction_smoothing_mm_s = 0.1;
  /// Integrate the energy accounts (CoupledEnergy) with the state.
  bool track_energy = false;
};

/// The energies of the coupled machine and what went in and out since reset(), J.
struct CoupledEnergy {
  double kinetic_J = 0.0;        ///< platform and struts
  double drive_kinetic_J = 0.0;  ///< ½ Σ m q̇²
  double elastic_J = 0.0;        ///< ½ Σ c (a − q)² (past the lost motion)
  double gravity_J = 0.0;
  double input_J = 0.0;       ///< ∫ Σ F q̇ + load · twist dt: the drives' work and the load's
  double dissipated_J = 0.0;  ///< ∫ Σ f q̇ + Σ D (ȧ − q̇) dt: friction and the elements' damping
  double stored_J() const { return kinetic_J + drive_kinetic_J + elastic_J + gravity_J; }
};

class CoupledMachine {
 public:
  /// The drives of `design` (their gains, imperfections and backlash) on `machine`'s elastic model; the
  /// transmission's stiffness from the machine file's servo: section in series with the struts'. Fails,
  /// naming the machine file and key, where the machine has no elastic model (no dynamics: section, no
  /// stiffness, angular actuators, no free platform) or a drive has no motor inertia. The machine must
  /// outlive the simulator.
  static Result<CoupledMachine> make(const Machine& machine, const LoopDesign& design, double loop_period_s,
                                     const CoupledOptions& options = {});
  ~CoupledMachine();
  CoupledMachine(CoupledMachine&&) noexcept;
  CoupledMachine& operator=(CoupledMachine&&) noexcept;

  /// At rest with the drives at `drive_position` (each the set point), the platform in static equilibrium
  /// under gravity and `load` near `guess`, every drive holding its element's force.
  Status reset(double time_s, const DriveVector& drive_position, const Pose& guess,
               const statics::Wrench& load = {});
  /// The process load on the platform (N, N·mm about the tool point), held until changed.
  void set_load(const statics::Wrench& load);
  /// One loop period: the regulators sample the drives against `reference` moving at `reference_speed`,
  /// and the machine moves for the period under the held commands. Fails where the platform leaves the
  /// mechanism's reach or the integration fails.
  Status step(const DriveVector& reference, const DriveVector& reference_speed);

  double time_s() const;
  /// The platform's actual pose (its tool point is where the tool is).
  Pose pose() const;
  const DriveVector& position() const { return position_; }  ///< the motors', mm
  const DriveVector& speed() const { return speed_; }
  const DriveVector& force() const { return force_; }  ///< the drives' forces, N
  const DriveVector& command() const;
  const ClampFlags& clamps() const;
  /// The energies now (track_energy for input_J and dissipated_J).
  Result<CoupledEnergy> energy() const;
  const dynamics::IntegrationCounters& counters() const;
  double loop_period_s() const;

 private:
  struct Impl;
  explicit CoupledMachine(std::unique_ptr<Impl> impl);
  void read_drives();
  std::unique_ptr<Impl> impl_;
  DriveVector position_ = DriveVector::Zero(), speed_ = DriveVector::Zero(), force_ = DriveVector::Zero();
};

}  // namespace pkm::servo
