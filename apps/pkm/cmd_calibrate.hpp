#pragma once
// pkm calibrate plan | simulate | identify (docs/calibration.md): one file per subcommand, the options they
// share here. The runs themselves are library calls (pipeline/calibration_run.hpp).
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "pipeline/calibration_run.hpp"

namespace pkm::cli {

/// The instrument options' text before it is checked (--ballbar-centre is a list).
struct CalibrateInstrumentText {
  std::string ballbar_centre;
};

/// --fixture, --plate-radius-mm, --ballbar-centre, --sigma-mm.
void add_calibrate_instrument_options(CLI::App& cmd, pipeline::CalibrationInstrument& instrument,
                                      CalibrateInstrumentText& text);
/// The checked instrument (the ballbar centre parsed).
Result<pipeline::CalibrationInstrument> calibrate_instrument(pipeline::CalibrationInstrument instrument,
                                                             const CalibrateInstrumentText& text);

/// --method, --poses (default 12), --box-mm, --box-deg, --strut-change-mm, --candidates, --held-out, --seed.
void add_calibrate_plan_options(CLI::App& cmd, pipeline::CalibrationPlanSpec& spec, std::string& method);
/// The spec with its method parsed; the seven-pose plan keeps its own count (n + 1) unless --poses was given.
Result<pipeline::CalibrationPlanSpec> calibrate_plan_spec(pipeline::CalibrationPlanSpec spec,
                                                          const std::string& method, bool poses_given);

/// The identifiability lines of a run's output ("rank 42 of 42 …", dropped combinations, warnings).
void print_calibrate_identifiability(const calibration::Identifiability& identifiability);

void add_calibrate_plan_command(CLI::App& calibrate, int& exit_code);
void add_calibrate_simulate_command(CLI::App& calibrate, int& exit_code);
void add_calibrate_identify_command(CLI::App& calibrate, int& exit_code);

}  // namespace pkm::cli
