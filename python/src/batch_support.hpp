#pragma once
// What the batch kinematics calls share: the `errors=` mode, the optional GIL release, the actuator-range
// test of the hot loops, and the exception for a failing row.
#include <pybind11/pybind11.h>

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include "core/result.hpp"
#include "machine/machine.hpp"

namespace pkm::python {

namespace py = pybind11;

/// errors="raise": the first failing row raises; errors="nan": failing rows become NaN.
enum class OnError { raise, nan };
/// Reads the `errors=` argument; ValueError for anything but "raise" or "nan".
OnError on_error_mode(const std::string& errors);

/// Releases the GIL for its lifetime when `release` (a batch large enough to be worth it), else does nothing.
class GilRelease {
 public:
  explicit GilRelease(bool release) {
    if (release) release_.emplace();
  }

 private:
  std::optional<py::gil_scoped_release> release_;
};

/// The machine's actuator range as two numbers (±inf where not given), for the test in the hot loops;
/// check_actuator_range says the same in words for the error.
struct ActuatorRange {
  double min = -HUGE_VAL;
  double max = HUGE_VAL;
  explicit ActuatorRange(const ActuatorLimits& limits)
      : min(limits.min.value_or(-HUGE_VAL)), max(limits.max.value_or(HUGE_VAL)) {}
  /// False also for NaN values.
  bool contains(const double* values, int count) const noexcept {
    bool inside = true;
    for (int j = 0; j < count; ++j) inside &= values[j] >= min && values[j] <= max;
    return inside;
  }
};

/// Why `pose` has no actuator values, in the library's words, as `pkm ik` reports it: the Result-returning
/// inverse kinematics' error, else (check_limits) the actuator range's as an unreachable pose.
Error unreachable_error(const Machine& machine, const Pose& pose, bool check_limits);

/// Raises the pkm exception for `error` (its class from the code) with "NAME[ROW]: " before the message and
/// the attribute `row` set (None for a single row given without a row axis).
[[noreturn]] void raise_row_error(const Error& error, const char* name, std::size_t row, bool single);

/// Fills `count` values with NaN (a failed row).
inline void fill_nan(double* values, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) values[i] = std::nan("");
}

}  // namespace pkm::python
