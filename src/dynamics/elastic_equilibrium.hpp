#pragma once
// Static equilibrium of the elastic machine (Smirnov 2019, (141) with q̈ = q̇ = 0): with
// the drives held at q, the platform settles where the elastic elements carry gravity (and a load),
//   G(pose) = applied(pose) − J_B(pose)ᵀ c (a(pose) − q) · 10³ = 0,
// a few millimetres' thousandths from the rigid pose FK(q) for the shipped machines (the static sag).
#include "dynamics/elastic_model.hpp"
#include "statics/wrench.hpp"

namespace pkm::dynamics {

/// The platform displaced by `displacement` (basis coordinates: mm and rad), as an exponential map: tool
/// point + v, rotation exp([ω]×) · R. To first order the displacement's rate is the twist's coordinates.
Pose displaced_pose(const ElasticModel& model, const Pose& pose, const CoordinateVector& displacement);

/// The platform's displacement from `from` to `to` in basis coordinates (the inverse of displaced_pose).
CoordinateVector pose_displacement(const ElasticModel& model, const Pose& from, const Pose& to);

/// The generalised force on the platform at rest, kg·mm/s² per coordinate: applied − J_Bᵀ F with the strut
/// forces F = c (a − q) (tension positive, N), which are also returned in `strut_force_N` when given.
/// `fixed_strut_force_N`, when given, replaces F (the preload held while the geometry moves: geometric
/// stiffness, natural_frequencies.hpp).
Result<CoordinateVector> rest_generalised_force(const ElasticModel& model, const Pose& pose,
                                                const ActuatorVector& drive_position_mm,
                                                const statics::Wrench& load = {},
                                                ActuatorVector* strut_force_N = nullptr,
                                                const ActuatorVector* fixed_strut_force_N = nullptr);

struct EquilibriumOptions {
  /// Newton stops when its step moves no platform joint more than this, mm (the rounding of a coordinate
  /// of 700 mm is ~10⁻¹³ mm).
  double step_tolerance_mm = 1e-12;
  int max_iterations = 50;
};

struct StaticEquilibrium {
  Pose pose;
  ActuatorVector drive_position_mm;
  ActuatorVector strut_force_N;  ///< tension positive
  int iterations = 0;
  double residual = 0.0;  ///< max |G| / max |applied| at the end
};

/// The equilibrium near `guess` with the drives held at `drive_position_mm` (the rigid pose is the natural
/// guess). Newton with the elastic elements' stiffness J_Bᵀ c J_B: the preload's geometric part is ~10⁻⁵ of
/// it on the shipped machines, so each step gains five digits. Fails where the pose leaves the reach, or the
/// iteration does not converge (a machine too soft to carry its weight).
Result<StaticEquilibrium> static_equilibrium(const ElasticModel& model,
                                             const ActuatorVector& drive_position_mm, const Pose& guess,
                                             const statics::Wrench& load = {},
                                             const EquilibriumOptions& options = {});

}  // namespace pkm::dynamics
