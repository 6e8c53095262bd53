#pragma once
// Drive steps as CSV (steps.csv), one row per servo period:
//   period,time_s,line,steps_1,…,steps_n,position_1,…,position_n
// Steps and position codes are integers and are written as such; the time is
// written with the shortest decimal that reads back as the same double, so the
// file holds the periods exactly (read_steps_csv gives back what was written).
// The file is staged (io/atomic_file.hpp) and appears only when finish()
// succeeds.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "interpolation/quantisation/step_period.hpp"
#include "io/atomic_file.hpp"

namespace pkm::interpolation {

inline constexpr const char* kStepsCsvName = "steps.csv";

/// DIRECTORY/steps.csv.
std::string steps_csv_path(const std::string& directory);

/// Room for one CSV row of up to kMaxActuators actuators with every number at
/// its widest.
using StepRowBuffer = std::array<char, 512>;

/// The header line `period,time_s,line,steps_1,…,position_n` with its '\n'.
std::string steps_csv_header(int actuators);

/// One period as a CSV row with its '\n', formatted into `buffer` (no
/// allocation); the view points into it.
std::string_view format_step_row(const StepPeriod& period, int actuators, StepRowBuffer& buffer);

class StepsCsvWriter : public StepSink {
 public:
  /// Stages the file `path` (usually steps_csv_path(dir)); only
  /// `header.actuators` is used.
  Status open(const std::string& path, const StepStreamHeader& header);
  /// Buffered; no allocation per period.
  Status write(const StepPeriod& period) override;
  /// Writes the rest and renames the file into place.
  Status finish() override;

 private:
  Status flush();

  StagedFile file_;
  std::string buffer_;
  int actuators_ = 0;
  bool open_ = false;
};

/// A steps.csv read back. `periods[k].position` as in the file; the start
/// positions are not stored in it.
struct StepsCsv {
  int actuators = 0;
  std::vector<StepPeriod> periods;
};

/// Reads a steps.csv; errors name the file and the line.
Result<StepsCsv> read_steps_csv(const std::string& path);

/// The same from the file's text (read_steps_csv reads the file and calls
/// this; the fuzz harness feeds it bytes); `source_name` is used in messages.
Result<StepsCsv> parse_steps_csv(std::string_view text, const std::string& source_name);

}  // namespace pkm::interpolation
