#include "interpolation/pose_tracker.hpp"

namespace pkm::interpolation {

PoseTracker::PoseTracker(const Machine& machine, const Pose& guess)
    : machine_(machine), workspace_(machine.mechanism->make_fk_workspace()), guess_(guess) {}

PoseTracker::PoseTracker(const PoseTracker& other)
    : machine_(other.machine_),
      workspace_(other.workspace_->clone()),
      options_(other.options_),
      guess_(other.guess_),
      solves_(other.solves_) {}

bool PoseTracker::solve(const double* actuators, Pose& pose) {
  const int n = machine_.mechanism->actuator_count();
  ActuatorVector values(n);
  for (int j = 0; j < n; ++j) values[j] = actuators[j];
  ++solves_;
  auto solution = machine_.mechanism->forward_warm(values, guess_, options_, *workspace_);
  if (!solution) return false;
  pose = guess_ = solution->pose;
  return true;
}

}  // namespace pkm::interpolation
