#pragma once
// The three drive control laws of Smirnov 2019, ch. 3, the two inverse-kinematics scenarios of Rusanov et
// al.'s glide machines (their §3), and what one path point costs under them.
//
//  increment (72)/(89)/(90): per step, max_j |ΔL_j| → min  (strut speed limited: step time ∝ the largest
//            change)
//  force     (75)/(92): per point, max_j |P_j| → min  (lower peak drive loads)
//  energy    (76)/(88)/(93): per step, Σ_j |ΔL_j·P_j| → min, bounded below by the required work |A_ext|
//  rotation  the "simple matrix" scenario: per step, the angle of the platform's rotation → min. Its least
//            value is the minimal rotation taking one tool axis to the next (Rodrigues, about n_old × n_new):
//            the spin about the tool axis moves only where the rest of the law asks for it
//  potential the "virtual potential" scenario: per point, max_j V(u_j) → min with u_j the actuator's place in
//            its range (0 at actuator_min, 1 at actuator_max) and V(u) = 1/u + 1/(1 − u) − 4, a barrier that
//            is 0 mid-range and grows without bound at either limit: the joints kept away from their limits
//
// A node is one candidate pose at one path point: its actuator positions and, when the law needs them, the
// actuator forces that hold the platform against the load there (statics, J^T P = −w, (73)/(91)).
#include <optional>
#include <string_view>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "redundancy/free_coordinates.hpp"
#include "statics/wrench.hpp"

namespace pkm::redundancy {

enum class Law { increment, force, energy, rotation, potential };
/// Whether the law's cost is that of a point alone (force, potential), which may also choose the start.
bool is_pointwise(Law law);
std::optional<Law> law_from_string(std::string_view name);
std::string_view to_string(Law law);

/// How a step's drive energy is counted (Smirnov 2019, §3.4.3).
enum class EnergyAccounting {
  no_recovery,   ///< Σ|ΔL·P|: a braking drive still draws |ΔL·P| (Smirnov 2019, (86))
  braking_free,  ///< Σ max(0, ΔL·P): braking costs nothing but returns nothing
  recovery,      ///< |Σ ΔL·P|: braking drives feed the others (equals the required work)
};
std::optional<EnergyAccounting> energy_accounting_from_string(std::string_view name);
std::string_view to_string(EnergyAccounting accounting);

/// Which forces the laws see (Smirnov 2019, §4.4): the statics of ch. 3 (the load and the weights, (91)), or
/// the rigid inverse dynamics at the programmed feed (src/dynamics/rigid_dynamics.hpp: every body's weight
/// and inertia; the machine file's dynamics: section). Under the dynamic model a step's forces are those of
/// the platform moving from the step's start pose to its end pose at the feed (the twist of the step over
/// its time, without acceleration: the step alone does not know the next one), so the energy law weighs the
/// velocity terms the faster feeds bring (Smirnov 2019, Table 3).
enum class ForceModel { statics, dynamics };
std::optional<ForceModel> force_model_from_string(std::string_view name);
std::string_view to_string(ForceModel model);

struct LawOptions {
  Law law = Law::increment;
  EnergyAccounting energy = EnergyAccounting::no_recovery;
  ForceModel forces = ForceModel::statics;
  /// Drive force limit |P_j| ≤ this (N); candidates above it are not admissible (energy law: Fig. 112).
  std::optional<double> force_limit_N;
  /// Keep-out margin round singularities (Smirnov, §3.3), as a share of the start pose's normalised Jacobian
  /// determinant (angle columns scaled by a characteristic length of the platform, divided by the product of
  /// the row norms: 1 for orthogonal struts, 0 at a singularity). Candidates below it are not admissible, nor
  /// those of the other sign (Smirnov 2019 tests only the sign). Relative, because well-built machines differ
  /// by an order of magnitude in the absolute value (planar tripod ≈ 0.1, ch3 hexapods ≈ 0.3).
  double singularity_margin = 0.1;
};

struct Node {
  ActuatorVector lengths;  ///< mm (or rad for angular actuators)
  ActuatorVector forces;   ///< N; zero when the law needs no forces (dynamic model: the static part)
  bool valid = false;
  // Under the dynamic force model, what the step into this node needs to move the platform:
  Pose pose;             ///< the candidate pose (complete under the dynamic model)
  statics::Wrench load;  ///< the process load here
  double step_s = 0.0;   ///< the step's time at the feed (0: a rapid or the start, forces at rest)
};

class LawEvaluator {
 public:
  /// `need_forces` also when only the report needs them (forces and energy for every law).
  LawEvaluator(const Machine& machine, const FreeCoordinates& free, const LawOptions& options,
               bool need_forces);

  const LawOptions& options() const { return options_; }
  const FreeCoordinates& free() const { return free_; }
  const Machine& machine() const { return machine_; }
  bool computes_forces() const { return need_forces_; }
  /// Sign of the Jacobian determinant at the start: candidates must keep it (no crossing a singular
  /// position, Smirnov 2019, §3.3).
  /// Fixes the branch and the keep-out threshold from the start pose; false when the start is singular.
  bool set_start(const Pose& start);

  /// IK (+ statics) of the pose at `point` with `values`. Invalid when out of reach or range, over the force
  /// limit, or (check_branch) on the other side of a singular position. Never allocates.
  bool evaluate(const PathPoint& point, const statics::Wrench& load, const FreeValues& values, Node& node,
                bool check_branch) const noexcept;
  /// Sign of det J at a pose (0: singular, within the keep-out margin, or unreachable).
  int branch_sign(const Pose& pose) const noexcept;
  /// det J normalised as LawOptions::singularity_margin says (NaN when unreachable).
  double normalized_determinant(const Pose& pose) const noexcept;

  /// The law's cost of the step from → to (pointwise laws: the cost of `to` alone).
  double step_cost(const Node& from, const Node& to) const noexcept;
  /// Σ_j |ΔL_j P_j| in the chosen accounting, N·mm.
  double step_energy_Nmm(const Node& from, const Node& to) const noexcept;
  /// The drive forces of the step from → to (N): the statics' at `to`, or under the dynamic model those of
  /// the platform moving through the step at the feed.
  ActuatorVector step_forces(const Node& from, const Node& to) const noexcept;
  /// The potential law's barrier at a node: its actuators' largest (0: every actuator mid-range).
  double limit_potential(const Node& node) const noexcept;

 private:
  const Machine& machine_;
  const FreeCoordinates& free_;
  LawOptions options_;
  bool need_forces_;
  /// The mechanism controls all six coordinates with six actuators and has a twist Jacobian: determinants
  /// and forces then use the twist form (fixed-size, free of the angle convention's own singularity).
  bool six_axis_twist_ = false;
  double characteristic_length_mm_ = 100.0;  ///< scales angle columns of J to lengths
  int branch_sign_ = 0;
  double min_determinant_ = 0.0;  ///< |normalised det J| below this counts as singular
};

}  // namespace pkm::redundancy
