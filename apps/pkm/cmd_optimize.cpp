// pkm optimize PROGRAM --machine M.yaml --law increment|force|energy|rotation|potential --free spin|all
//   [--bounds LO,HI] [--step-mm S] [--parts fixed|adaptive] [--load SPEC] [--solver greedy|global] --out
//   OUT.ngc [--json]:
// Smirnov's post-processor (§3.6). Chooses the coordinates the operation leaves free by a drive control law
// and writes the program with A B C; prints how much the law saves against holding them constant.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pipeline/optimize_job.hpp"
#include "planning/motion_plan.hpp"
#include "program/part_program.hpp"
#include "program_options.hpp"
#include "progress_display.hpp"
#include "redundancy_options.hpp"

namespace pkm::cli {

namespace {

void print_optimize_text(const nlohmann::json& s, const std::string& out_path) {
  const double reduction =
      s["const_sum_mm"].get<double>() > 0.0
          ? 100.0 * (1.0 - s["opt_sum_mm"].get<double>() / s["const_sum_mm"].get<double>())
          : 0.0;
  std::cout << fmt::format("{}: {} law, {} solver, free {} ({} points, step {} mm)\n",
                           s["program"].get<std::string>(), s["law"].get<std::string>(),
                           s["solver"].get<std::string>(), fmt::join(s["free_coordinates"], ", "),
                           s["points"].get<int>(), s["step_mm"].get<double>());
  std::cout << fmt::format("  parts       {} {} written, at most {} per block\n",
                           s["parts_written"].get<int>(), s["parts"].get<std::string>(),
                           s["largest_parts"].get<int>());
  std::cout << fmt::format(
      "  Σ max|ΔL|   const {:.3f} mm   law {:.3f} mm   ({:+.2f} %: machining time at strut "
      "speed limits)\n",
      s["const_sum_mm"].get<double>(), s["opt_sum_mm"].get<double>(), -reduction);
  std::cout << fmt::format("  peak force  const {:.1f} N   law {:.1f} N\n",
                           s["peak_force_const_N"].get<double>(), s["peak_force_opt_N"].get<double>());
  std::cout << fmt::format("  energy      const {:.3f} J   law {:.3f} J   (required work {:.3f} J)\n",
                           s["energy_const_J"].get<double>(), s["energy_opt_J"].get<double>(),
                           s["required_work_J"].get<double>());
  const auto& names = s["free_coordinates"];
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::cout << fmt::format(
        "  {:<10}  start {:.3f} deg, used {:.3f} … {:.3f} deg (bounds {:.3f} … {:.3f})\n",
        names[i].get<std::string>(), s["start_deg"][i].get<double>(), s["free_range_deg"][i][0].get<double>(),
        s["free_range_deg"][i][1].get<double>(), s["bounds_deg"][i][0].get<double>(),
        s["bounds_deg"][i][1].get<double>());
  }
  if (s.contains("whole_path")) {
    std::cout << fmt::format(
        "  greedy      Σ {:.3f} mm in {:.3f} s; whole path Σ {:.3f} mm in {:.3f} s\n",
        s["greedy"]["increment_sum_mm"].get<double>(), s["greedy"]["seconds"].get<double>(),
        s["whole_path"]["increment_sum_mm"].get<double>(), s["whole_path"]["seconds"].get<double>());
  }
  std::cout << fmt::format("  written     {}\n", out_path);
}

}  // namespace

void add_optimize_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "optimize", "choose the free coordinates of a program by a drive control law; write it with A B C");
  auto program_path = std::make_shared<std::string>();
  auto machine_path = std::make_shared<std::string>();
  auto out_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto report_file = std::make_shared<std::string>();
  auto arguments = std::make_shared<RedundancyArguments>();
  auto program_arguments = std::make_shared<ProgramArguments>();
  cmd->add_option("program", *program_path,
                  "part program: G-code (X Y Z) or CL data (told apart by content; --format)")
      ->required();
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  cmd->add_option("--out", *out_path, "the post-processed G-code program (.ngc)")->required();
  cmd->add_flag("--json", *json, "print the summary as JSON");
  cmd->add_option("--report", *report_file,
                  "also write the HTML report (chosen vs constant, forces, 3-D view)");
  add_redundancy_options(*cmd, *arguments, true);
  add_program_options(*cmd, *program_arguments);
  cmd->callback([=, &exit_code] {
    auto options = redundancy_options(*arguments);
    if (!options) {
      exit_code = report_error("optimize", options.error());
      return;
    }
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("optimize", machine.error());
      return;
    }
    pipeline::OptimizeJob job{
        *program_path, program_arguments->options(), std::move(*options), *out_path, *report_file, {}};
    ProgressDisplay progress("optimize", "reading the program");
    job.progress = progress.sink();
    auto result = pipeline::run_optimize_job(*machine, job);
    progress.finish();
    if (!result) {
      exit_code = report_error("optimize", result.error());
      return;
    }
    const nlohmann::json& summary = result->summary;
    if (*json) {
      print_json(summary);
      return;
    }
    print_optimize_text(summary, *out_path);
  });
}

}  // namespace pkm::cli
