#pragma once
// The execution stream: the interpolated motion as a controller takes it while it runs (LinuxCNC through
// pkm's HAL component pkmexec and linuxcnc/pkm_feed.py, docs/linuxcnc.md). Text, one record per line, written
// period by period as the interpolation computes them (a program of any length streams with bounded memory):
//
//   # pkm execution stream 1: MACHINE, 6 drives, period 0.001 s, step 0.001
//   start,P1,…,Pn                     the drives' whole-step positions before the first period
//   p,LINE,I1,…,In,P1,…,Pn            one servo period: the program line, the ideal values at its end (in
//                                     steps, shortest round-trip decimals) and the whole-step positions
//   end                               the program's last period has been written
//
// A stream without its `end` line was cut short (the program failed, or its writer died): a controller must
// then stop, within the drives' limits, after the last period it has.
#include <cstdio>
#include <string>

#include "core/result.hpp"
#include "interpolation/quantisation/step_period.hpp"
#include "io/atomic_file.hpp"

namespace pkm::formats {

class ExecutionStreamWriter {
 public:
  /// `target` "-" is standard output (written as the periods come); any other path a file that appears
  /// complete when finish() succeeds.
  Status open(const std::string& target, const std::string& machine, int drives, double period_s,
              double step);
  /// Writes the start record before the first period. No allocation per period.
  Status write(const interpolation::StepPeriod& period);
  /// The `end` record; flushes standard output, or renames the file into place.
  Status finish();

 private:
  Status put(std::string_view text);

  bool to_stdout_ = false;
  StagedFile file_;
  std::string buffer_;
  int drives_ = 0;
  bool started_ = false;
};

}  // namespace pkm::formats
