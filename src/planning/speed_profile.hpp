#pragma once
// The speed along the path, planned on a grid of path samples s_0 < s_1 < … (the "unfiltered" profile).
//
// Each sample carries a speed cap V_i (feed, actuator speeds, curvature) and a tangential acceleration cap
// A_i (path and actuator accelerations). A forward pass (accelerate as hard as allowed) and a backward pass
// (brake in time for every later cap) give the fastest profile with v_i ≤ V_i and |v²_{i+1} − v²_i| ≤ 2 A Δs
// between samples: constant acceleration on each interval, the textbook's S̈ = const law (textbook §2.6),
// with the braking point found from the remaining path by the correct kinematic formula.
//
// Jerk is limited afterwards by a moving-average filter of length T on the path parameter (servo_stream.hpp),
// which keeps the tool exactly on the path. The filter averages speeds over the last T seconds, so before the
// final passes every cap is lowered to the smallest cap within reach of that window (`erode_caps`).
#include <vector>

namespace pkm::planning {

struct ProfileSamples {
  std::vector<double> s;          ///< path parameter, strictly increasing
  std::vector<double> speed_cap;  ///< V_i, path units per second (0 at stops)
  std::vector<double> accel_cap;  ///< A_i, path units per second²
  std::vector<double> speed;      ///< the planned v_i
  std::vector<double> hold_s;  ///< time to stay at rest at sample i (dwell and filter settling); 0 elsewhere
  std::vector<char> stop;      ///< the motion comes to rest at sample i (corner, dwell, program ends)
  /// The index along the whole path of element 0: a streaming planner keeps a window of the samples.
  std::size_t first = 0;

  std::size_t size() const { return s.size(); }
  void resize(std::size_t n);
  /// Forgets the first `count` samples (a window moving along the path): `first` grows by `count`.
  void erase_front(std::size_t count);
};

/// Forward and backward passes: fills `speed` from the caps (v = 0 at the first and last sample).
void plan_speeds(ProfileSamples& samples);

/// Lowers the caps so that a window-T moving average of any profile below them stays below the caps given:
/// sample j's speed cap V_j (and its acceleration cap) spreads over the path within T·V_j + margin of s_j.
/// That reach is enough: a profile no faster than V_j there needs at least T to cross it, so when the
/// filtered position is at s_j the whole window lies inside it, and the window's average is at most V_j. (It
/// depends on the cap, not on the plan: a reach from the unfiltered plan's speed, T·v + a·T²/2, slowed a
/// whole rapid to the speed of a slow corner 17 mm ahead.) Spreads never cross a stop: the profile rests
/// there for T, so no filter window holds motion from both sides; and a stop's own zero cap is met by that
/// rest, not by slowing its neighbours.
void erode_caps(ProfileSamples& samples, double window_s, double margin);

/// The unfiltered motion in time: at sample i the profile is at s_i with speed v_i at time `time_s[i]`; after
/// holding `hold_s[i]` it leaves with constant acceleration to sample i+1.
struct TimedProfile {
  std::vector<double> time_s;  ///< arrival time at sample i
  double end_time_s = 0.0;     ///< arrival at the last sample plus its hold
};
TimedProfile time_profile(const ProfileSamples& samples);

/// Cursor over the timed profile: the unfiltered position at increasing times, O(1) amortised. Over a window
/// (ProfileSamples::first), the samples from the one before `index()` on must be kept.
class ProfileCursor {
 public:
  ProfileCursor(const ProfileSamples& samples, const TimedProfile& timed)
      : samples_(samples), timed_(timed) {}
  double position_at(double t_s);
  /// The sample (its index along the whole path) the profile left last.
  std::size_t index() const { return index_; }

 private:
  const ProfileSamples& samples_;
  const TimedProfile& timed_;
  std::size_t index_ = 0;
};

}  // namespace pkm::planning
