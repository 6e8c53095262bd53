#pragma once
// The tool's compliance with the machine frame elastic too (the full model; Rusanov et al.'s
// FE model, docs/stiffness_frame.md): a finite-element model of
//  - the frame's beams (beam_element.hpp; six DOF per free node, fixed nodes removed),
//  - the platform as a rigid master node at the tool point (the twist (d mm, θ rad) about it; for a
//    reduced-DOF mechanism only the twists T q it allows, as strut_compliance does: its passive constraints
//    stay rigid and q has the mechanism's degrees of freedom),
//  - every strut as an axial bar (pin-jointed) between its base joint A_j, rigidly offset from its frame node
//    n (it moves by u_n + θ_n × (A_j − x_n); on the ground when the node is fixed or there is no frame), and
//    its platform joint B_j (d + θ × (B_j − p)).
// K u = f is assembled into a sparse matrix whose pattern is fixed at construction (ordered once by minimum
// degree and analysed once); a pose refills the values and factorises (L D Lᵀ) into storage made at
// construction, so evaluating along a path does not allocate. The compliance about the tool point is the
// platform block of K⁻¹, C = T (K⁻¹)_pp Tᵀ: with the platform's unknowns ordered last, the factor's trailing
// block is their Schur complement L_pp D_p L_ppᵀ = ((K⁻¹)_pp)⁻¹, so it needs no solve.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "statics/wrench.hpp"
#include "stiffness/frame_structure.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::stiffness {

/// The model's answer to a load at one pose.
struct FrameDeflection {
  Vector6 tool = Vector6::Zero();  ///< (d mm, θ rad) of the platform about the tool point, base frame
  /// Each strut's axial force, N, tension positive (as ToolDeflection; statics' P_j is its negative).
  ActuatorVector strut_tension_N;
  /// (u mm, φ rad) of every frame node (FrameParameters::nodes order), zero at fixed nodes.
  std::vector<Vector6> node_displacement;
};

class FrameModel {
 public:
  /// The model of `mechanism` (kept by pointer: it must outlive the model) with the struts and frame of
  /// `stiffness`. An empty frame puts every base joint on the ground. Fails when the frame is a mechanism
  /// (singular, naming the machine file and the line of `stiffness.frame`), or when the struts do not match
  /// the mechanism (unsupported).
  static Result<FrameModel> make(const Mechanism& mechanism, const StiffnessParameters& stiffness);

  FrameModel(FrameModel&&) noexcept;
  FrameModel& operator=(FrameModel&&) noexcept;
  ~FrameModel();

  /// The 6 × 6 compliance about the tool point at `pose` (ToolCompliance as strut_compliance gives it; the
  /// struts' stiffness c_j(L) are the bars' own, without the joints and carriages). Fails where the pose is
  /// out of reach, or where nothing holds the platform in some allowed direction (singular, "unbounded
  /// compliance"). Not thread-safe: the model's buffers are reused (one model per thread).
  Result<ToolCompliance> compliance(const Pose& pose);

  /// The deflection under the wrench `load` (force N, moment N·mm about the tool point, base frame) on the
  /// platform, into `out` (its storage reused: make it with make_deflection()). Fails as compliance().
  Status deflection(const Pose& pose, const statics::Wrench& load, FrameDeflection& out);
  FrameDeflection make_deflection() const;

  /// Unknowns of the assembled system: six per free frame node and the platform's allowed twists.
  int unknowns() const;
  /// Non-zeros of the factor L (the fill the minimum-degree ordering leaves).
  long factor_nonzeros() const;

 private:
  struct Impl;
  explicit FrameModel(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::stiffness
