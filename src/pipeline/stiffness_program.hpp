#pragma once
// `pkm stiffness` as one library call: a part program's tool deflection under a cutting load at
// every path point, the machine's stiffness model from its file (or one asked for), and, if asked, the
// pre-compensated program whose deflected tool follows the nominal path. Written as an output set
// (points.csv, summary.json, optionally compliance.csv and the program) that replaces a previous run's only
// when all of it succeeded. docs/stiffness.md.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/progress.hpp"
#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"
#include "statics/load_model.hpp"
#include "stiffness/tool_deflection.hpp"

namespace pkm::pipeline {

struct StiffnessJob {
  std::string program_path;             ///< G-code, or CL data (told apart by content)
  ProgramOptions program_options;       ///< tool table, subroutine path, parameter file
  statics::LoadModel load;              ///< the cutting load (statics/load_model.hpp)
  std::optional<StiffnessModel> model;  ///< unset: the machine file's
  double step_mm = 1.0;                 ///< moves are cut into points no farther apart
  bool compliance_matrices = false;     ///< also DIR/compliance.csv: the 6 × 6 compliance at every point
  /// Where to write the pre-compensated program ("": none): CL data when the path is .cl/.cls/.apt or the
  /// program states tool axes, else G-code with A B C.
  std::string compensated_path;
  /// Also DIR/bode.csv: the tool's dynamic compliance (the dynamics: section's masses and springs,
  /// docs/dynamic_compliance.md) at the point of the largest error along the tool axis.
  bool frequency_response = false;
  std::string out_directory;
  std::string report_path;  ///< the HTML report of the run ("": none)
  ProgressSink progress;    ///< told the phase, how far the analysis is and its program line, now and then
};

struct CompensationSummary {
  double max_residual_mm = 0.0;
  double max_residual_rad = 0.0;
  int max_iterations = 0;
  double max_correction_mm = 0.0;  ///< largest |x_cmd − x_nom|
  int max_correction_line = 0;
};

struct StiffnessProgramResult {
  stiffness::DeflectionStatistics statistics;
  StiffnessModel model = StiffnessModel::struts;
  std::optional<CompensationSummary> compensation;
  nlohmann::json summary;  ///< summary.json as written
};

Result<StiffnessProgramResult> stiffness_program(const Machine& machine, const StiffnessJob& job);

}  // namespace pkm::pipeline
