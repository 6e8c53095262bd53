#pragma once
// The speed profile planned through a bounded look-ahead window, sample by sample as the path arrives: what
// a controller does that reads the program while it moves (LinuxCNC's and Klipper's queues of moves).
//
// The whole-path planner (speed_profile.hpp) lowers the caps by the jerk filter's reach (erode_caps), then
// runs a forward and a backward pass over every sample. Here the samples wait in a window, and a sample's
// speed is handed on once no later sample can change it:
//  - its caps are final once the path pushed beyond it is longer than the farthest reach of any cap,
//    T·V_max + margin (V_max: the fastest cap the machine allows), so no later spread reaches back to it;
//  - the backward pass runs from the last sample with final caps, assuming the motion stops there. Where
//    that assumed stop does not lower a sample's forward speed, more path can only raise the backward
//    speeds, so the sample's speed is the whole path's, and so is every speed before it.
// So wherever the window holds enough path, the plan equals the whole-path plan to the bit. Where it
// does not (a window of `max_length`, `max_samples` or `max_moves` full before braking distance is found),
// the window is binding: its first quarter is handed on as planned to stop at the window's end, which the
// motion can always do within every limit, and the next window starts from that speed. Binding places are
// counted (the run's summary reports them).
//
// Memory is bounded by the window (plus the reach behind it the caps' spreads need), not by the path.
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "planning/speed_profile.hpp"

namespace pkm::planning {

/// A planning sample as the sampling gives it: the caps before the jerk filter's erosion.
struct RawSample {
  double s = 0.0;          ///< path parameter, strictly increasing from sample to sample
  double speed_cap = 0.0;  ///< path units per second; 0 at stops
  double accel_cap = 0.0;  ///< path units per second²
  double hold_s = 0.0;     ///< rest at this sample (dwell, filter settling)
  bool stop = false;       ///< the motion comes to rest here
  int move = 0;            ///< canonical move the sample lies on (the window's bound in moves)
};

/// A sample whose speed is final: the eroded caps and the planned speed.
struct PlannedSample {
  double s = 0.0;
  double speed_cap = 0.0;
  double accel_cap = 0.0;
  double speed = 0.0;
  double hold_s = 0.0;
  bool stop = false;
};

struct LookaheadSettings {
  double filter_window_s = 0.0;  ///< T of the jerk filter, whose reach erodes the caps (speed_profile.hpp)
  double erosion_margin = 0.0;
  /// No sample's speed cap is above this (the machine's fastest rapid, feed or angular speed).
  double fastest_cap = std::numeric_limits<double>::infinity();
  /// The window: at most this much path, this many samples and this many moves wait for their speeds.
  double max_length = std::numeric_limits<double>::infinity();
  std::size_t max_samples = std::numeric_limits<std::size_t>::max();
  int max_moves = std::numeric_limits<int>::max();
};

class LookaheadProfile {
 public:
  explicit LookaheadProfile(const LookaheadSettings& settings);

  /// The next sample along the path (s beyond the last pushed). Samples whose speed becomes final are
  /// appended to planned().
  void push(const RawSample& sample);
  /// The path ends at the sample pushed last: every waiting sample is planned, the last at rest.
  void finish();

  /// Final samples in path order, not yet taken by the caller; clear_planned() after reading them.
  const std::vector<PlannedSample>& planned() const { return planned_; }
  void clear_planned() { planned_.clear(); }

  /// How many times the window was full before its speeds were final (where it set the speed).
  long binding_count() const { return binding_count_; }
  /// The most samples that waited at once (the window's memory).
  std::size_t peak_window_samples() const { return peak_window_; }

 private:
  void advance(bool at_end);
  std::size_t last_final_caps(bool at_end) const;
  bool window_full() const;
  void erode_window();
  std::size_t plan_window(std::size_t last, bool at_end);
  void hand_on(std::size_t last);
  void drop_history();

  LookaheadSettings settings_;
  double reach_ = 0.0;     ///< the farthest any cap spreads: T·V_max + margin
  ProfileSamples window_;  ///< history (final, kept for the spreads) then waiting samples
  std::vector<double> raw_speed_cap_, raw_accel_cap_;
  std::vector<int> move_;
  std::size_t first_waiting_ = 0;         ///< index in window_ of the oldest sample without a final speed
  std::array<double, 2> planned_caps_{};  ///< speed and acceleration caps of the sample handed on last
  std::size_t pushed_since_advance_ = 0;
  std::size_t full_window_step_ = 1;  ///< pushes between two plannings of a full window
  std::vector<PlannedSample> planned_;
  long binding_count_ = 0;
  std::size_t peak_window_ = 0;
};

/// The whole-path profile through the look-ahead window: fills `samples.speed` and the eroded caps, as
/// erode_caps + plan_speeds do wherever the window is not binding. `sample_move` gives each sample's move.
/// Returns how many times the window was binding.
long plan_speeds_lookahead(ProfileSamples& samples, const std::vector<int>& sample_move,
                           const LookaheadSettings& settings);

}  // namespace pkm::planning
