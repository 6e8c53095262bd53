#pragma once
// `pkm play --to`: each period the player releases as a steps.csv row (after the same header line). To a
// FIFO, a device or stdout the row is written when the period is released (one write each, so the reader at
// the other end sees it at once); a regular file is staged and appears only when the whole run has been
// played.
#include <string>
#include <string_view>

#include "interpolation/quantisation/step_period.hpp"
#include "io/atomic_file.hpp"

namespace pkm::formats {

class StepLineSink : public interpolation::StepSink {
 public:
  StepLineSink() = default;
  ~StepLineSink() override;
  StepLineSink(const StepLineSink&) = delete;
  StepLineSink& operator=(const StepLineSink&) = delete;

  /// `target`: empty for nowhere, "-" for stdout, else a path. Opening a FIFO waits for its reader. Errors
  /// (io) name the target.
  Status open(const std::string& target, int actuators);
  Status write(const interpolation::StepPeriod& period) override;
  Status finish() override;

 private:
  Error failure(int error_number) const;
  Status put(std::string_view text);

  std::string target_;
  int actuators_ = 0;
  int descriptor_ = -1;
  bool staged_ = false;
  StagedFile file_;
};

}  // namespace pkm::formats
