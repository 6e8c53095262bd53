#pragma once
// The accepted interval of a job's numeric parameter, defined once in the library: the library checks every
// job against it (whoever calls), and the CLI takes its option checks from the same definition.
#include <string_view>

#include "core/result.hpp"

namespace pkm::pipeline {

struct ParameterRange {
  std::string_view name;  ///< the parameter, as messages and Python name it ("box_mm")
  double low;
  double high;
  bool low_inclusive = true;  ///< false: low itself is refused ("> 0")
  std::string_view unit;      ///< "mm", "deg", "" for a count
  bool whole = false;         ///< only whole numbers (counts)
};

/// `value` within `range`, or ErrorCode::bad_input naming the parameter ("box_mm 20000: expected 0 … 10000
/// mm").
Status check_in_range(const ParameterRange& range, double value);

}  // namespace pkm::pipeline
