#pragma once
// The parameters of an RS274/NGC program as LinuxCNC 2.9 keeps them:
//  - numbered #1–#5601 (LinuxCNC 2.9 has 5602 slots; #0 and #5602 are "out of range" in expressions, #0
//    reads as 0 in DEBUG comments); #1–#30 are the arguments of the subroutine call
//    that is running (each call level has its own), the rest are global;
//  - named locals #<name> (visible in the subroutine call that set them, or in the main program);
//  - named globals #<_name> (visible everywhere);
//  - predefined read-only names (#<_x>, #<_metric>, #<_current_tool>, …) that the executor answers through
//    PredefinedParameters, so their value is always the machine state's.
// Names are case-insensitive and blanks inside them are ignored, as in LinuxCNC. Reading a value never
// allocates; setting a new name does once.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace pkm::program::ngc {

constexpr int kParameterCount = 5602;  ///< #0 … #5601 (RS274NGC_MAX_PARAMETERS of LinuxCNC 2.9)

/// Answers the read-only predefined named parameters (#<_x>, #<_metric> …) from the machine state.
class PredefinedParameters {
 public:
  virtual ~PredefinedParameters() = default;
  /// The value of a predefined name (lower case, without blanks, with its leading '_'), or nullopt when the
  /// name is not a predefined one.
  virtual std::optional<double> predefined(std::string_view name) const = 0;
};

// ParameterStore (ngc_parameter_store.hpp) offers at least:
//   double get(int number) const;                 // #0 … #5601; #1–#30 of the running call level
//   void set(int number, double value);
//   std::optional<double> named(std::string_view name) const;   // normalised name; locals, then globals
//   void set_named(std::string_view name, double value);
//   Status load_var_file(const std::string& path);              // LinuxCNC .var format
//   Status save_var_file(const std::string& path) const;        // atomically (temporary file + rename)
class ParameterStore;

}  // namespace pkm::program::ngc
