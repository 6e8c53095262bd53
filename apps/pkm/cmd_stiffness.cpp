// pkm stiffness PROGRAM --machine M.yaml --load LOAD --out DIR [--model M] [--step-mm S]
//   [--compliance-matrices] [--compensate FILE] [--frequency-response] [--report FILE] [--json]:
// the tool's deflection under the cutting load at every point of a part program (points.csv, summary.json;
// src/pipeline/stiffness_program.hpp, docs/stiffness.md), and, with --compensate, the program pre-compensated
// for it.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "number_options.hpp"
#include "pipeline/stiffness_program.hpp"
#include "program_options.hpp"
#include "progress_display.hpp"
#include "stiffness/compliance_model.hpp"

namespace pkm::cli {

void add_stiffness_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "stiffness",
      "the tool's deflection under a cutting load along a part program, and its pre-compensation");
  auto job = std::make_shared<pipeline::StiffnessJob>();
  auto machine_path = std::make_shared<std::string>();
  auto load_text = std::make_shared<std::string>();
  auto model_name = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto program_arguments = std::make_shared<ProgramArguments>();
  cmd->add_option("program", job->program_path,
                  "part program: G-code, or CL data (told apart by content; --format)")
      ->required();
  cmd->add_option("--machine", *machine_path, "machine file (YAML) with a stiffness: section")->required();
  cmd->add_option(
         "--load", *load_text,
         "the cutting load: key=value pairs (tangential=N,normal=N,axial=N,force=X:Y:Z,...), or @FILE "
         "(YAML load cases, or CSV per program line)")
      ->required();
  cmd->add_option("--out", job->out_directory, "directory for points.csv and summary.json")->required();
  cmd->add_option("--model", *model_name,
                  "struts, struts_joints or frame (default: the fullest the machine file describes)");
  // Beyond a metre between points nothing on a machine pkm models would be seen.
  cmd->add_option("--step-mm", job->step_mm, "moves are cut into points at most this far apart, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 1000.0, false, true, "mm"}));
  cmd->add_flag("--compliance-matrices", job->compliance_matrices,
                "also compliance.csv: the 6 × 6 tool compliance at every point");
  cmd->add_option("--compensate", job->compensated_path,
                  "also write the program pre-compensated for the deflection here (CL data for .cl/.cls/.apt "
                  "or tool-axis programs, else G-code)");
  cmd->add_flag("--frequency-response", job->frequency_response,
                "also bode.csv: the tool's dynamic compliance at the point of the largest error (dynamics: "
                "section), a Bode plot in the report");
  cmd->add_option("--report", job->report_path, "also write the HTML report of the run to this file");
  add_program_options(*cmd, *program_arguments);
  cmd->add_flag("--json", *json, "print the summary as JSON");
  cmd->callback([=, &exit_code] {
    if (!model_name->empty()) {
      job->model = stiffness::stiffness_model_from_string(*model_name);
      if (!job->model) {
        exit_code = report_error(
            "stiffness", make_error(ErrorCode::bad_input,
                                    fmt::format("--model: expected struts, struts_joints or frame, got '{}'",
                                                *model_name)));
        return;
      }
    }
    auto load = statics::parse_load_spec(*load_text);
    Status lines = load ? statics::check_load_lines(*load, job->program_path) : Status(load.error());
    if (!lines) {
      exit_code =
          report_error("stiffness", make_error(lines.error().code, "--load: " + lines.error().message));
      return;
    }
    job->load = std::move(*load);
    job->program_options = program_arguments->options();
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("stiffness", machine.error());
      return;
    }
    ProgressDisplay progress("stiffness", "reading the program");
    job->progress = progress.sink();
    auto result = pipeline::stiffness_program(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("stiffness", result.error());
      return;
    }
    if (*json) {
      print_json(result->summary);
      return;
    }
    const stiffness::DeflectionStatistics& s = result->statistics;
    std::cout << fmt::format("{}: {} points ({} cutting) on {} ({}), {} model\n", job->program_path, s.points,
                             s.cutting_points, machine->name, *machine_path,
                             stiffness::to_string(result->model));
    std::cout << fmt::format("  along the tool axis  max {:.3f} µm (line {}), rms {:.3f} µm\n",
                             s.max_normal_mm * 1e3, s.max_normal_line, s.rms_normal_mm * 1e3);
    std::cout << fmt::format("  tool deflection      max {:.3f} µm (line {})\n", s.max_deflection_mm * 1e3,
                             s.max_deflection_line);
    std::cout << fmt::format("  strut force          max {:.1f} N (strut {}, line {})\n", s.max_strut_force_N,
                             s.max_strut_force_strut, s.max_strut_force_line);
    if (result->compensation) {
      const pipeline::CompensationSummary& k = *result->compensation;
      std::cout << fmt::format(
          "  pre-compensated      {} (corrections up to {:.3f} µm at line {}; residual {:.2g} µm, {} "
          "iterations at most)\n",
          job->compensated_path, k.max_correction_mm * 1e3, k.max_correction_line, k.max_residual_mm * 1e3,
          k.max_iterations);
    }
    std::cout << fmt::format("  written              {}/points.csv, summary.json{}{}\n", job->out_directory,
                             job->compliance_matrices ? ", compliance.csv" : "",
                             job->frequency_response ? ", bode.csv" : "");
  });
}

}  // namespace pkm::cli
