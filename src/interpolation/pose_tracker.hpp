#pragma once
// Forward kinematics along a run: each solve starts from the previous pose (the tool moves a few µm per
// call) and keeps the mechanism's FK workspace (Mechanism::forward_warm, the servo-loop form: a hexapod
// reuses the factorisation of the previous call). One tracker per sequence of nearby poses.
#include <memory>

#include "machine/machine.hpp"

namespace pkm::interpolation {

class PoseTracker {
 public:
  PoseTracker(const Machine& machine, const Pose& guess);
  /// A copy continues from the same state (the workspace is cloned) without touching the original's.
  PoseTracker(const PoseTracker& other);
  PoseTracker(PoseTracker&&) noexcept = default;
  /// FK of `actuators` (count = the mechanism's); the pose becomes the next guess. False if FK fails (the
  /// guess is kept). No allocation.
  bool solve(const double* actuators, Pose& pose);
  const Pose& last() const { return guess_; }
  void reset(const Pose& guess) {
    guess_ = guess;
    workspace_->reset();
  }
  long solves() const { return solves_; }

 private:
  const Machine& machine_;
  std::unique_ptr<FkWorkspace> workspace_;  ///< made once, here: solve() does not allocate
  FkOptions options_;
  Pose guess_;
  long solves_ = 0;
};

}  // namespace pkm::interpolation
