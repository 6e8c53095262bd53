#include "machine/actuator_offsets.hpp"

#include <fmt/format.h>

#include <cassert>

namespace pkm {

ActuatorOffsets::ActuatorOffsets(std::unique_ptr<Mechanism> inner, const ActuatorVector& offsets)
    : inner_(std::move(inner)), offsets_(offsets) {
  // A broken contract, not an input error: the offsets' group is checked before anything is wrapped.
  assert(offsets_.size() == inner_->actuator_count());
  home_ = inner_->home();
}

Result<ActuatorVector> ActuatorOffsets::inverse(const Pose& pose) const {
  auto values = inner_->inverse(pose);
  if (!values) return values;
  *values -= offsets_;
  return values;
}

namespace {

Error wrong_reading_count(const ActuatorVector& readings, int count) {
  return make_error(
      ErrorCode::bad_input,
      fmt::format("{} drive readings given where the mechanism has {} drives", readings.size(), count));
}

}  // namespace

Result<FkSolution> ActuatorOffsets::forward(const ActuatorVector& actuators, const Pose& guess,
                                            const FkOptions& options) const {
  if (actuators.size() != offsets_.size()) return wrong_reading_count(actuators, actuator_count());
  const ActuatorVector geometric = actuators + offsets_;
  return inner_->forward(geometric, guess, options);
}

Result<FkSolution> ActuatorOffsets::forward_warm(const ActuatorVector& actuators, const Pose& guess,
                                                 const FkOptions& options, FkWorkspace& workspace) const {
  if (actuators.size() != offsets_.size()) return wrong_reading_count(actuators, actuator_count());
  // Fixed capacity: the sum does not allocate.
  const ActuatorVector geometric = actuators + offsets_;
  return inner_->forward_warm(geometric, guess, options, workspace);
}

bool ActuatorOffsets::forward_warm_quiet(const ActuatorVector& actuators, const Pose& guess,
                                         const FkOptions& options, FkWorkspace& workspace, FkSolution& out,
                                         ErrorCode& failure) const {
  if (actuators.size() != offsets_.size()) {
    failure = ErrorCode::bad_input;
    return false;
  }
  const ActuatorVector geometric = actuators + offsets_;
  return inner_->forward_warm_quiet(geometric, guess, options, workspace, out, failure);
}

Result<std::vector<FkSolution>> ActuatorOffsets::forward_all(const ActuatorVector& actuators,
                                                             const FkOptions& options) const {
  if (actuators.size() != offsets_.size()) return wrong_reading_count(actuators, actuator_count());
  const ActuatorVector geometric = actuators + offsets_;
  return inner_->forward_all(geometric, options);
}

Result<AssemblyModes> ActuatorOffsets::assembly_modes(const ActuatorVector& actuators,
                                                      const FkOptions& options) const {
  if (actuators.size() != offsets_.size()) return wrong_reading_count(actuators, actuator_count());
  const ActuatorVector geometric = actuators + offsets_;
  return inner_->assembly_modes(geometric, options);
}

bool ActuatorOffsets::actuator_values(const Pose& pose, double* out) const noexcept {
  if (!inner_->actuator_values(pose, out)) return false;
  for (int j = 0; j < offsets_.size(); ++j) out[j] -= offsets_[j];
  return true;
}

bool ActuatorOffsets::actuator_values_at(AngleConvention convention, const PoseVector& coordinates,
                                         double* out) const noexcept {
  if (!inner_->actuator_values_at(convention, coordinates, out)) return false;
  for (int j = 0; j < offsets_.size(); ++j) out[j] -= offsets_[j];
  return true;
}

std::vector<GeometryGroup> ActuatorOffsets::geometry_parameters() const {
  std::vector<GeometryGroup> groups = inner_->geometry_parameters();
  groups.push_back(actuator_offsets_group(offsets_, inner_->actuators_are_angles()));
  return groups;
}

Result<std::unique_ptr<Mechanism>> ActuatorOffsets::with_geometry(
    const std::vector<GeometryGroup>& groups) const {
  if (auto ok = check_geometry_groups(geometry_parameters(), groups); !ok) return ok.error();
  const std::vector<GeometryGroup> inner_groups(groups.begin(), groups.end() - 1);
  auto inner = inner_->with_geometry(inner_groups);
  if (!inner) return inner.error();
  const std::vector<double>& values = groups.back().values;
  const ActuatorVector offsets =
      Eigen::Map<const ActuatorVector>(values.data(), static_cast<Eigen::Index>(values.size()));
  return with_actuator_offsets(std::move(inner.value()), offsets);
}

GeometryGroup actuator_offsets_group(const ActuatorVector& offsets, bool angles) {
  return {std::string(kActuatorOffsetsKey),
          "dL",
          {""},
          angles ? "rad" : "mm",
          static_cast<int>(offsets.size()),
          {offsets.data(), offsets.data() + offsets.size()}};
}

std::unique_ptr<Mechanism> with_actuator_offsets(std::unique_ptr<Mechanism> inner,
                                                 const ActuatorVector& offsets) {
  return std::make_unique<ActuatorOffsets>(std::move(inner), offsets);
}

Result<std::unique_ptr<Mechanism>> with_actuator_offset_parameters(const Mechanism& m) {
  const std::vector<GeometryGroup> groups = m.geometry_parameters();
  auto clone = m.with_geometry(groups);
  if (!clone) return clone.error();
  if (!groups.empty() && groups.back().key == kActuatorOffsetsKey) return clone;
  return with_actuator_offsets(std::move(clone.value()), ActuatorVector::Zero(m.actuator_count()));
}

}  // namespace pkm
