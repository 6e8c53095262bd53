#pragma once
// Which of the six pose coordinates (x, y, z, angle 1, angle 2, angle 3) a mechanism controls.
#include <array>

namespace pkm {

struct AxisMask {
  std::array<bool, 6> controlled{};
  int count() const {
    int n = 0;
    for (bool c : controlled) n += c ? 1 : 0;
    return n;
  }
  static AxisMask all() { return {{true, true, true, true, true, true}}; }
  static AxisMask translations() { return {{true, true, true, false, false, false}}; }
};

}  // namespace pkm
