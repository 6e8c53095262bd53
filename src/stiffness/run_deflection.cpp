#include "stiffness/run_deflection.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/rotation.hpp"

namespace pkm::stiffness {

Result<RunDeflection> RunDeflection::make(const Machine& machine, const statics::LoadModel& load,
                                          std::function<Status(const DeflectionTick&)> on_tick) {
  auto stiffness = strut_stiffness_of(machine);
  if (!stiffness) return stiffness.error();
  return RunDeflection(machine, load, *stiffness, std::move(on_tick));
}

RunDeflection::RunDeflection(const Machine& machine, const statics::LoadModel& load,
                             StiffnessParameters stiffness,
                             std::function<Status(const DeflectionTick&)> on_tick)
    : machine_(&machine),
      load_(&load),
      stiffness_(stiffness),
      on_tick_(std::move(on_tick)),
      tool_axis_platform_(machine.mechanism->home().rotation.transpose() * Eigen::Vector3d::UnitZ()) {}

Status RunDeflection::add(double time_s, int line, const Pose& pose, bool cutting) {
  const auto due = window_.add(Sample{time_s, line, pose, cutting});
  return due.index >= 0 ? evaluate(due.index, due.at_rest) : ok_status();
}

Status RunDeflection::finish() {
  if (const auto due = window_.finish(); due.index >= 0) {
    if (Status last = evaluate(due.index, due.at_rest); !last) return last;  // the end, at rest
  }
  if (summary_.cutting_ticks > 0)
    summary_.rms_normal_mm = std::sqrt(normal_square_sum_ / summary_.cutting_ticks);
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
  auto compliance = strut_compliance(*machine_->mechanism, stiffness_, s.pose);
  if (!compliance) {
    return Error{compliance.error().code,
                 fmt::format("at {:.3f} s: {}", s.time_s, compliance.error().message),
                 ErrorLocation{"", s.line, 0, ""}};
  }
  Eigen::Matrix<double, 6, 1> wrench;
  wrench << tick.load.force_N, tick.load.moment_Nmm;
  const Eigen::Matrix<double, 6, 1> displacement = compliance->compliance * wrench;
  tick.deflection_mm = displacement.head<3>();
  tick.rotation_rad = displacement.tail<3>().norm();
  tick.normal_mm = tick.deflection_mm.dot(compliance->pose.rotation * tool_axis_platform_);

  ++summary_.ticks;
  if (s.cutting) {
    ++summary_.cutting_ticks;
    normal_square_sum_ += tick.normal_mm * tick.normal_mm;
  }
  if (std::abs(tick.normal_mm) > summary_.max_normal_mm) {
    summary_.max_normal_mm = std::abs(tick.normal_mm);
    summary_.max_normal_line = s.line;
    summary_.max_normal_time_s = s.time_s;
  }
  if (tick.deflection_mm.norm() > summary_.max_deflection_mm) {
    summary_.max_deflection_mm = tick.deflection_mm.norm();
    summary_.max_deflection_line = s.line;
  }
  if (on_tick_) return on_tick_(tick);
  return ok_status();
}

}  // namespace pkm::stiffness
