#pragma once
// Small helpers the executor's files share: what a motion code is, and whole numbers.
#include <cmath>
#include <limits>

#include "program/gcode_block.hpp"

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

/// The nearest int; a value beyond int's reach (a program may write any number) is INT_MIN, which no tool,
/// L or P word accepts, so the caller's range check refuses it.
inline int whole(double value) {
  if (!(std::abs(value) < 1e9)) return std::numeric_limits<int>::min();
  return static_cast<int>(std::lround(value));
}

/// G10, G28, G30, G52, G92 and G43.1 take the block's axis words for themselves: the block does not move
/// by them (G28/G30 make their own moves).
inline bool codes_take_axis_words(const gcode::Block& b) {
  const gcode::Code& non_modal = b.g[gcode::g_non_modal];
  const bool takes =
      non_modal.is(100) || non_modal.is(280) || non_modal.is(300) || non_modal.is(520) || non_modal.is(920);
  return takes || b.g[gcode::g_tool_length].is(431);
}

}  // namespace pkm::program::ngc::executor_support
