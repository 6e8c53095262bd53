#pragma once
// The planned motion at the servo rate: one tick every period h, giving the commanded pose on the path and
// the actuator positions from inverse kinematics.
//
// Jerk limiting: the unfiltered path parameter s(t) of the speed profile (constant acceleration between
// planning samples) passes through a moving average over the last N ticks,
//   s_f[k] = (1/N) Σ_{m=0}^{N−1} s[k − m],   T = N·h = 2·a_max / j_max,
// the classic FIR acceleration/deceleration of CNC interpolators, applied here to the path parameter before
// the coordinate transform (beyond textbook §2.1.3) so the tool never leaves the path. The filtered speed
// is an average of speeds (≤ the largest), its acceleration (v[k] − v[k−N])/T is within a_max, and its jerk
// within 2·a_max/T = j_max: an S-curve. At stops the profile rests for T, so the filtered motion arrives at
// rest.
//
// Per tick: no allocation (the ring buffer is sized once).
#include <limits>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "planning/speed_profile.hpp"

namespace pkm::planning {

struct ServoTick {
  long index = 0;
  double time_s = 0.0;
  double s = 0.0;           ///< path parameter
  double path_speed = 0.0;  ///< ds/dt over the last period (path units per second)
  int segment = 0;
  int line = 0;  ///< source line of the program
  Pose pose;     ///< commanded pose (controlled point, base frame)
  ActuatorVector actuators;
  /// The path segment the tick is on, as the plan had it: a consumer on another thread than the stream reads
  /// the tick, never the plan's window (which the stream extends and releases).
  path::Segment on_segment;
  /// The path's point at the middle of the period before this tick, where the run monitor measures the path
  /// error (ServoStream::with_mid_points; not for the first tick).
  path::PathPoint mid_point;
  bool has_mid_point = false;
};

class PlanProducer;

class ServoStream {
 public:
  /// With a `source`, `plan` is the window it plans into (plan_producer.hpp): the stream asks it for the plan
  /// a tick needs and releases what the ticks have passed. Without, `plan` is whole.
  ServoStream(const MotionPlan& plan, const Machine& machine, PlanProducer* source = nullptr);
  /// The next tick; false after the last. A failing inverse kinematics (which the planning grid should have
  /// caught) ends the stream with error().
  bool next(ServoTick& tick);
  /// Also the path's point at every mid-period (ServoTick::mid_point), for the path error.
  void with_mid_points(bool wanted) { mid_points_ = wanted; }
  /// With a source: the path from segment `segment` on stays, also behind the ticks (a consumer lagging
  /// behind them still reads it). Default: only what the ticks still need.
  void hold_path_from(int segment) { hold_segment_ = segment; }
  /// The ticks of the whole motion; 0 while a source is still planning (the end is not known yet).
  long tick_count() const { return last_tick_ == kUnknownEnd ? 0 : last_tick_ + 1; }
  const std::optional<Error>& error() const { return error_; }

 private:
  const MotionPlan& plan_;
  const Machine& machine_;
  PlanProducer* source_;
  ProfileCursor cursor_;
  std::vector<double> ring_;
  double sum_ = 0.0;
  long k_ = 0;
  static constexpr long kUnknownEnd = std::numeric_limits<long>::max();
  long last_tick_ = kUnknownEnd;
  int hint_ = 0;
  int hold_segment_ = std::numeric_limits<int>::max();
  double previous_s_ = 0.0;
  bool mid_points_ = false;
  std::optional<Error> error_;
};

}  // namespace pkm::planning
