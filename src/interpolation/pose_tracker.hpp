#pragma once
// Forward kinematics along a run: each solve starts from the previous pose (the tool moves a few µm per
// call), and on a hexapod reuses the factorisation of the previous call (Hexapod::forward with a
// PlatformFkWorkspace, the servo-loop form). One tracker per sequence of nearby poses.
#include "machine/hexapod.hpp"
#include "machine/machine.hpp"

namespace pkm::interpolation {

class PoseTracker {
 public:
  PoseTracker(const Machine& machine, const Pose& guess);
  /// FK of `actuators` (count = the mechanism's); the pose becomes the next guess. False if FK fails (the
  /// guess is kept). No allocation.
  bool solve(const double* actuators, Pose& pose);
  const Pose& last() const { return guess_; }
  void reset(const Pose& guess) {
    guess_ = guess;
    workspace_.reset();
  }
  long solves() const { return solves_; }

 private:
  const Machine& machine_;
  const Hexapod* hexapod_;
  PlatformFkWorkspace<6> workspace_;
  FkOptions options_;
  Pose guess_;
  long solves_ = 0;
};

}  // namespace pkm::interpolation
