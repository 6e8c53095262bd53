#pragma once
// The parameter memory of an RS274/NGC program (see ngc_parameters.hpp for the rules LinuxCNC 2.9 follows):
// numbered #0–#5601, #1–#30 saved and replaced on every O-word call and restored on its return, named locals
// per call level and named globals (#<_name>). Names are normalised here (lower case, no blanks) so callers
// may pass them as written.
//
// No allocation on reads, on setting a number, on calls and returns once the call stack has grown, nor on
// setting a name that the same call level has set before: a level's names keep their storage when the level
// returns and are only marked stale (by a generation count), so a loop that calls a subroutine setting
// locals does not allocate per call.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/result.hpp"
#include "program/ngc_parameters.hpp"

namespace pkm::program::ngc {

constexpr int kCallArgumentCount = 30;  ///< #1 … #30

class ParameterStore {
 public:
  ParameterStore();

  /// #number; #0 and numbers out of range read as 0 (the reader refuses them before asking).
  double get(int number) const {
    return (number > 0 && number < kParameterCount) ? values_[static_cast<std::size_t>(number)] : 0.0;
  }
  /// Sets #number; #0 and numbers out of range are ignored (the reader refuses them before asking).
  void set(int number, double value) {
    if (number > 0 && number < kParameterCount) values_[static_cast<std::size_t>(number)] = value;
  }
  /// LinuxCNC's read-only numbered parameters (5021–5029, 5400–5413, 5420–5428): a program cannot set them.
  static bool is_read_only(int number);

  /// A named parameter: `_name` is global, any other name is local to the running call level. The name may
  /// be given as written (any case, with blanks).
  std::optional<double> named(std::string_view name) const;
  void set_named(std::string_view name, double value);
  /// Creates `name` with value 0 when it does not exist yet (LinuxCNC creates the target of `#<name>=` while
  /// reading the line, so the right-hand side may already read it).
  void declare_named(std::string_view name);

  /// Enters an O-word call: saves #1–#30 of the caller and sets them to `arguments` (the rest 0).
  void push_call(const double* arguments, int count);
  /// Leaves a call: restores the caller's #1–#30 and forgets the callee's named locals.
  void pop_call();
  int call_level() const { return level_; }

  /// Reads a LinuxCNC `.var` file (lines `NUMBER VALUE`, numbers increasing). As LinuxCNC does, every
  /// numbered parameter not in the file becomes 0 (then #5599, which enables DEBUG output, 1). A missing
  /// file is not an error (LinuxCNC creates it on the next save).
  Status load_var_file(const std::string& path);
  /// Writes the `.var` file: the parameters listed in the file already there (or loaded from it) plus the
  /// ones LinuxCNC always keeps (G28/G30 homes, G92 offsets, coordinate systems 1–9 with their rotations,
  /// the selected system 5220), as `NUMBER<tab>VALUE` with six decimals. Written to a temporary file and
  /// renamed, so a crash never leaves a truncated file.
  Status save_var_file(const std::string& path) const;

  /// Normalises a parameter name as LinuxCNC reads it: lower case, blanks removed.
  static void normalise_name(std::string_view name, std::string& out);

 private:
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  struct Slot {
    double value = 0.0;
    std::uint64_t generation = 0;  ///< valid while equal to its level's generation
  };
  using NameMap = std::unordered_map<std::string, Slot, NameHash, std::equal_to<>>;
  struct Level {
    NameMap names;
    std::uint64_t generation = 1;
    std::array<double, kCallArgumentCount> saved_arguments{};  ///< the caller's #1–#30
  };

  /// The normalised form of `name`, in `scratch` when it had to change.
  static std::string_view normalised(std::string_view name, std::string& scratch);
  const Level& level_for(std::string_view normalised_name) const;
  Level& level_for(std::string_view normalised_name);

  std::vector<double> values_;
  std::vector<Level> levels_;  ///< [0] the main program (and the globals), grown on calls, never shrunk
  int level_ = 0;
  std::vector<int> loaded_numbers_;  ///< the numbers the last .var file listed (saved again)
  mutable std::string scratch_;
};

}  // namespace pkm::program::ngc
