#include "stiffness/compliance_model.hpp"

#include <fmt/format.h>

#include "stiffness/frame_model.hpp"

namespace pkm::stiffness {

std::string_view to_string(StiffnessModel model) {
  switch (model) {
    case StiffnessModel::struts:
      return "struts";
    case StiffnessModel::struts_joints:
      return "struts_joints";
    case StiffnessModel::frame:
      return "frame";
  }
  return "struts";
}

std::optional<StiffnessModel> stiffness_model_from_string(std::string_view name) {
  for (StiffnessModel model :
       {StiffnessModel::struts, StiffnessModel::struts_joints, StiffnessModel::frame}) {
    if (name == to_string(model)) return model;
  }
  return std::nullopt;
}

Result<ComplianceModel> ComplianceModel::make(const Machine& machine, std::optional<StiffnessModel> model) {
  auto parameters = strut_stiffness_of(machine);
  if (!parameters) return parameters.error();
  ComplianceModel out;
  out.mechanism_ = machine.mechanism.get();
  out.parameters_ = *parameters;
  if (model) out.parameters_.model = *model;
  if (out.parameters_.model == StiffnessModel::frame) {
    if (out.parameters_.frame.empty()) {
      return Error{ErrorCode::bad_input,
                   fmt::format("{}: stiffness.frame: the frame model needs a frame of beams in the machine "
                               "file's stiffness: section (docs/stiffness_frame.md)",
                               machine.source),
                   ErrorLocation{machine.source, parameters->line, 0, "stiffness.frame"}};
    }
    auto frame = FrameModel::make(*machine.mechanism, out.parameters_);
    if (!frame) return frame.error();
    out.frame_ = std::make_shared<FrameModel>(std::move(*frame));
  }
  return out;
}

Result<ToolCompliance> ComplianceModel::at(const Pose& pose) const {
  if (frame_) {
    auto compliance = frame_->compliance(pose);
    // The frame's nodes move too: a strut's tension is not its platform end's stretch alone.
    if (compliance) compliance->tensions_from_stretch = false;
    return compliance;
  }
  return strut_compliance(*mechanism_, parameters_, pose);
}

}  // namespace pkm::stiffness
