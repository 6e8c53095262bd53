#pragma once
// Small helpers the executor's files share: what a motion code is, and whole numbers.
#include <cmath>

namespace pkm::program::ngc::executor_support {

/// Tool numbers and turns are ints; larger values are typing errors, not programs.
constexpr double kLargestCount = 1e6;

inline bool is_cycle(int motion) {
  return motion == 730 || (motion >= 810 && motion <= 890);
}

inline bool is_arc(int motion) {
  return motion == 20 || motion == 30;
}

inline bool is_probe(int motion) {
  return motion >= 382 && motion <= 385;
}

inline bool is_whole(double value) {
  return std::abs(value - std::round(value)) < 1e-6;
}

inline int whole(double value) {
  return static_cast<int>(std::lround(value));
}

}  // namespace pkm::program::ngc::executor_support
