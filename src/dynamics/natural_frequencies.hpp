#pragma once
// Natural frequencies and mode shapes of the elastic machine at a pose (beyond Smirnov 2019, §4.5: linearise
// about equilibrium: K = ∂²Π/∂q² (platform block, with q_1..q_6 clamped) and M, then solve det(K − ω²M) = 0).
// The drives are clamped at the commanded pose's actuator values, the platform sags to its static equilibrium
// under gravity (elastic_equilibrium.hpp), and about that equilibrium
//   M δ̈ + K δ = 0,   K = J_Bᵀ diag(c) J_B + K_geo,
// δ the platform's displacement in the basis coordinates (exponential map, whose rate is the twist). K_geo is
// the preload's part: the struts' equilibrium forces F* held while the geometry turns, and gravity's
// generalised force as the bodies move, K_geo = −∂(applied − J_Bᵀ F*)/∂δ, by central differences (it is
// symmetric at an equilibrium, where the potential's gradient vanishes; the residual asymmetry is reported).
// Its size relative to the first term is about F*/(c·l) (strut force over stiffness times length), 10⁻⁵ on
// the shipped machines. M is equations_of_motion's mass matrix at the equilibrium. The problem is solved by
// Eigen's GeneralizedSelfAdjointEigenSolver.
#include <vector>

#include "dynamics/elastic_equilibrium.hpp"

namespace pkm::dynamics {

struct ModalOptions {
  /// Include K_geo (the gravity preload's geometric stiffness). Without gravity and load it is zero.
  bool geometric_stiffness = true;
  /// Central-difference step of K_geo: mm for translations, this over the platform's size for rotations.
  /// The functions differenced vary over the struts' length (hundreds of mm): truncation ~(h/l)² ≈ 10⁻⁹.
  double difference_step_mm = 1e-2;
  EquilibriumOptions equilibrium;
};

struct NaturalModes {
  StaticEquilibrium equilibrium;  ///< where the platform rests, with the drives' positions and strut forces
  int count = 0;                  ///< the basis' coordinates: 6, or 3 (planar), or 2 (a planar point)
  CoordinateVector frequency_Hz;  ///< ascending
  /// Column i: mode i as basis coordinates (mm, rad), scaled so that the largest motion of a platform joint
  /// or the tool point is 1 mm, its largest component (rotations × platform size) positive.
  CoordinateMatrix shape;
  CoordinateMatrix mass;             ///< M, kg (mm coordinates) and kg·mm² (rad coordinates)
  CoordinateMatrix stiffness;        ///< K, kg/s² per mm or rad (N/mm × 10³), symmetrised
  double geometric_share = 0.0;      ///< max |K_geo| / max |K|
  double geometric_asymmetry = 0.0;  ///< max |K_geo − K_geoᵀ| / max |K|, before symmetrising
};

/// Modes about the static equilibrium with the drives clamped at `commanded`'s actuator values. Fails where
/// the pose is out of reach, singular, or unstable (a non-positive ω², e.g. a preload that buckles it).
Result<NaturalModes> natural_modes(const ElasticModel& model, const Pose& commanded,
                                   const ModalOptions& options = {});

/// The lowest natural frequency at each pose (Hz), NaN where natural_modes fails there (out of reach,
/// singular): a map of the machine's dynamic stiffness over a grid of poses.
std::vector<double> lowest_frequency_map(const ElasticModel& model, const std::vector<Pose>& poses,
                                         const ModalOptions& options = {});

}  // namespace pkm::dynamics
