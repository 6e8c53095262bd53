#pragma once
// The last three servo ticks of a stream, for what is evaluated at a tick from its neighbours (central
// differences: the twist, the direction of travel). Tick k is evaluated when tick k + 1 arrives; the first
// tick at once and the last at the end, both at rest (every run starts and ends there).
#include <array>

#include "core/pose.hpp"

namespace pkm {

/// A commanded tick of a planned run: when, from which program line, where, and whether it cuts.
struct CommandedTick {
  double time_s = 0.0;
  int line = 0;
  Pose pose;
  bool cutting = true;  ///< false on rapids
};

template <class Sample>
class TickWindow {
 public:
  /// What to evaluate after a step of the stream: the window index and whether the tick is at rest.
  struct Due {
    int index = -1;  ///< −1: nothing yet
    bool at_rest = false;
  };

  /// Adds the next tick: the first is due at once (at rest), from the third on the one before it.
  Due add(const Sample& sample) {
    samples_[0] = samples_[1];
    samples_[1] = samples_[2];
    samples_[2] = sample;
    ++count_;
    if (count_ == 1) return {2, true};
    if (count_ >= 3) return {1, false};
    return {};
  }
  /// After the last add(): the last tick, at rest (nothing when there was only one, already evaluated).
  Due finish() const { return count_ >= 2 ? Due{2, true} : Due{}; }

  /// 0: the tick before the one due, 1: the tick due mid-stream, 2: the newest.
  const Sample& operator[](int index) const { return samples_[index]; }

 private:
  std::array<Sample, 3> samples_{};
  long count_ = 0;
};

}  // namespace pkm
