#include "interpolation/pose_tracker.hpp"

namespace pkm::interpolation {

PoseTracker::PoseTracker(const Machine& machine, const Pose& guess)
    : machine_(machine), hexapod_(dynamic_cast<const Hexapod*>(machine.mechanism.get())), guess_(guess) {}

bool PoseTracker::solve(const double* actuators, Pose& pose) {
  const int n = machine_.mechanism->actuator_count();
  ActuatorVector values(n);
  for (int j = 0; j < n; ++j) values[j] = actuators[j];
  ++solves_;
  if (hexapod_ != nullptr) {
    auto solution = hexapod_->forward(values, guess_, options_, workspace_);
    if (!solution) return false;
    pose = guess_ = solution->pose;
    return true;
  }
  auto solution = machine_.mechanism->forward(values, guess_, options_);
  if (!solution) return false;
  pose = guess_ = solution->pose;
  return true;
}

}  // namespace pkm::interpolation
