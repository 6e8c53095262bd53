#include "stiffness/run_deflection.hpp"

#include <fmt/format.h>

namespace pkm::stiffness {

Result<RunDeflection> RunDeflection::make(const Machine& machine, const statics::LoadModel& load,
                                          std::function<Status(const DeflectionTick&)> on_tick) {
  auto model = ComplianceModel::make(machine);
  if (!model) return model.error();
  return RunDeflection(machine, load, std::move(*model), std::move(on_tick));
}

RunDeflection::RunDeflection(const Machine& machine, const statics::LoadModel& load, ComplianceModel model,
                             std::function<Status(const DeflectionTick&)> on_tick)
    : load_(&load),
      model_(std::move(model)),
      on_tick_(std::move(on_tick)),
      tool_axis_platform_(machine.mechanism->home().rotation.transpose() * Eigen::Vector3d::UnitZ()) {
  summary_.model = model_.model();
}

Status RunDeflection::add(double time_s, int line, const Pose& pose, bool cutting) {
  const auto due = window_.add(Sample{time_s, line, pose, cutting});
  return due.index >= 0 ? evaluate(due.index, due.at_rest) : ok_status();
}

Status RunDeflection::finish() {
  if (const auto due = window_.finish(); due.index >= 0) {
    if (Status last = evaluate(due.index, due.at_rest); !last) return last;  // the end, at rest
  }
  summary_.finish();
  return ok_status();
}

Status RunDeflection::evaluate(int index_in_window, bool at_rest) {
  const Sample& s = window_[index_in_window];
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  if (!at_rest) {
    velocity =
        (window_[2].pose.position_mm - window_[0].pose.position_mm) / (window_[2].time_s - window_[0].time_s);
  }
  DeflectionTick tick;
  tick.time_s = s.time_s;
  tick.line = s.line;
  tick.load =
      load_->wrench_at(statics::travel_load_point(s.pose, velocity, tool_axis_platform_, s.line, s.cutting));
  auto compliance = model_.at(s.pose);
  if (!compliance) {
    return Error{compliance.error().code,
                 fmt::format("at {:.3f} s: {}", s.time_s, compliance.error().message),
                 ErrorLocation{"", s.line, 0, ""}};
  }
  const ToolDeflection deflection =
      deflect(*compliance, tick.load, compliance->pose.rotation * tool_axis_platform_);
  tick.deflection_mm = deflection.displacement_mm;
  tick.rotation_rad = deflection.rotation_rad.norm();
  tick.normal_mm = deflection.normal_mm;
  const double before = summary_.max_normal_mm;
  summary_.add(summary_.points, s.line, s.cutting, deflection);
  if (summary_.max_normal_mm != before) summary_.max_normal_time_s = s.time_s;
  if (on_tick_) return on_tick_(tick);
  return ok_status();
}

}  // namespace pkm::stiffness
