// pkm modes-margin PROGRAM --machine M.yaml [--samples N] [--out FILE.csv] [--json]:
// the assembly-mode margin along a planned program (src/workspace/modes_margin.hpp): at poses
// evenly spaced in time along the run `pkm plan` would make, the smallest actuator change that brings the
// machine onto a singular configuration where its assembly mode can meet another one, and the real assembly
// modes of the pose's actuator values with the nearest other one. Prints the smallest margin with its program
// line; --out writes every sample as a CSV (atomically, after everything is computed).
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "formats/modes_margin_output.hpp"
#include "number_options.hpp"
#include "pipeline/modes_margin_job.hpp"
#include "planning/path_sampling.hpp"
#include "program_options.hpp"
#include "progress_display.hpp"

namespace pkm::cli {
namespace {

// A million poses take about a quarter of an hour on the ch5 hexapod: more is a typo, not a wish.
constexpr double kMaxMarginSamples = 1e6;

struct ModesMarginArguments {
  std::string program_path, machine_path, out_path;
  ProgramArguments program;
  int samples = 200;
  bool json = false;
};

void print_modes_margin(const Machine& machine, const workspace::ProgramModesMargin& r,
                        const ModesMarginArguments& a) {
  const Mechanism& mech = *machine.mechanism;
  const workspace::ModesMarginSummary& s = r.summary;
  const char* unit = formats::margin_unit(mech);
  std::cout << fmt::format("{} on {} ({}): {} poses over {:.3f} s\n", a.program_path, machine.name,
                           machine.source, s.samples, r.duration_s);
  if (s.min_margin) {
    const workspace::ModesMarginSample& low = r.samples[*s.min_margin];
    const workspace::ModesMarginSample& high = r.samples[*s.max_margin];
    std::cout << fmt::format("  assembly-mode margin   min {:.3f} {} at line {}, t {:.3f} s, {}\n",
                             formats::margin_in_user_unit(mech, low.margin.margin_mm), unit, low.line,
                             low.time_s, planning::program_pose_text(machine, low.margin.pose));
    std::cout << fmt::format("                         nearest singular configuration {}{}\n",
                             planning::program_pose_text(machine, low.margin.singular_pose),
                             low.margin.note.empty() ? "" : " (an upper bound: " + low.margin.note + ")");
    std::cout << fmt::format("                         max {:.3f} {} at line {}, t {:.3f} s\n",
                             formats::margin_in_user_unit(mech, high.margin.margin_mm), unit, high.line,
                             high.time_s);
  }
  if (s.margins_found < s.samples) {
    std::cout << fmt::format("  no singular configuration found from {} of the {} poses\n",
                             s.samples - s.margins_found, s.samples);
  }
  if (s.margins_bounded > 0) {
    std::cout << fmt::format(
        "  at {} poses no search converged: their margins are the nearest singular configuration found on a "
        "line from the pose, upper bounds\n",
        s.margins_bounded);
  }
  if (s.modes_enumerated > 0) {
    std::cout << fmt::format("  real assembly modes    {} … {} ({} poses enumerated)\n", s.min_real_modes,
                             s.max_real_modes, s.modes_enumerated);
  }
  if (s.nearest_other_mode) {
    const workspace::ModesMarginSample& n = r.samples[*s.nearest_other_mode];
    std::cout << fmt::format(
        "  nearest other mode     {:.3f} mm and {:.3f} deg away at line {}, t {:.3f} s\n",
        n.modes.nearest_other_position_mm, n.modes.nearest_other_rotation_deg, n.line, n.time_s);
  }
  if (s.modes_enumerated < s.samples && !s.modes_note.empty()) {
    std::cout << fmt::format("  other assembly modes   not enumerated: {}\n", s.modes_note);
  }
  if (!a.out_path.empty()) std::cout << fmt::format("  written {}\n", a.out_path);
}

int run_modes_margin(const ModesMarginArguments& a) {
  const std::string command = "modes-margin";
  auto machine = load_machine_or_report(a.machine_path);
  if (!machine) return report_error(command, machine.error());
  ProgressDisplay progress("modes-margin", "reading the program");
  pipeline::ModesMarginJob job{a.program_path, a.program.options(), {}, a.out_path, progress.sink()};
  job.margin.samples = a.samples;
  auto result = pipeline::run_modes_margin_job(*machine, job);
  progress.finish();
  if (!result) return report_error(command, result.error());
  if (a.json) {
    print_json(result->summary);
    return 0;
  }
  print_modes_margin(*machine, result->margin, a);
  return 0;
}

}  // namespace

void add_modes_margin_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "modes-margin",
      "assembly-mode margin along a program: the smallest actuator change that brings the machine onto a "
      "singular configuration where its assembly mode can meet another, and the other assembly modes");
  auto a = std::make_shared<ModesMarginArguments>();
  cmd->add_option("program", a->program_path,
                  "part program: G-code, or CL data (told apart by content; --format)")
      ->required();
  cmd->add_option("--machine", a->machine_path, "machine file (YAML)")->required();
  cmd->add_option("--samples", a->samples, "poses between the start and the end, evenly spaced in time")
      ->capture_default_str()
      ->check(number_in({1.0, kMaxMarginSamples, true, true, "", true}));
  cmd->add_option("--out", a->out_path, "also write every pose's margin and modes to this CSV file");
  cmd->add_flag("--json", a->json, "print the summary as JSON");
  add_program_options(*cmd, a->program);
  cmd->callback([a, &exit_code] { exit_code = run_modes_margin(*a); });
}

}  // namespace pkm::cli
