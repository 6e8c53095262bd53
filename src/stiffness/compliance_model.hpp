#pragma once
// The tool's compliance under the stiffness model a machine file describes (or one asked for), whatever the
// model: every consumer (a run's deflection, a program's deflection, the NC pre-compensation, the maps, the
// CLI) asks this one object, so a new model is added here and nowhere else.
//
//   StiffnessModel::struts          the struts' springs only: K = Gᵀ diag(c) G (strut_compliance.hpp)
//   StiffnessModel::struts_joints   each strut in series with its joints, carriage drive and guide
//   StiffnessModel::frame           with the frame of beams as well (frame_model.hpp)
#include <memory>
#include <optional>

#include "machine/machine.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::stiffness {

class FrameModel;

std::string_view to_string(StiffnessModel model);
std::optional<StiffnessModel> stiffness_model_from_string(std::string_view name);

class ComplianceModel {
 public:
  /// The machine's model, or `model` instead (a simpler one to compare with, or a fuller one the file
  /// describes). Fails where the machine gives its struts no stiffness (strut_stiffness_of), or where the
  /// model asked for needs what the file does not describe (a frame), naming the file and key.
  static Result<ComplianceModel> make(const Machine& machine, std::optional<StiffnessModel> model = {});

  /// The compliance about the tool point at `pose`: errors as strut_compliance (out of reach, "unbounded
  /// compliance" at a singular pose, the frame's own singularity). With the frame model it reuses the
  /// model's buffers: one ComplianceModel per thread (copies share them).
  Result<ToolCompliance> at(const Pose& pose) const;

  StiffnessModel model() const { return parameters_.model; }
  const StiffnessParameters& parameters() const { return parameters_; }
  const Mechanism& mechanism() const { return *mechanism_; }

 private:
  const Mechanism* mechanism_ = nullptr;
  StiffnessParameters parameters_;
  std::shared_ptr<FrameModel> frame_;  ///< StiffnessModel::frame: the assembled frame, its factorisation
};

}  // namespace pkm::stiffness
