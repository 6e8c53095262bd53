// pkm servo PLAN_DIR --machine M.yaml [--out DIR] [--decoupled] [--inertia-every N] [--report FILE] [--json]:
// a planned run through the drives' cascaded servo loops (the machine file's servo: section): following error
// per drive, contour error and lag at the tool, where the limits acted, the coupling check, and each loop's
// step response and margins (src/pipeline/servo_program.hpp, docs/servo.md); --report writes the plan's HTML
// report with the servo plots (report/servo_plots.hpp).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iostream>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pipeline/servo_program.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

namespace {

// The drives' imperfections the run had, if any: once for every drive when they are alike.
void print_imperfections(const servo::LoopDesign& design, bool angular) {
  const double shown = angular ? 180.0 / 3.14159265358979323846 : 1.0;
  const char* length = angular ? "deg" : "mm";
  const char* force = angular ? "N·mm" : "N";
  std::vector<std::string> drives;
  for (int j = 0; j < design.drives; ++j) {
    const servo::ChannelGains& g = design.channels[j];
    std::vector<std::string> parts;
    if (g.friction_static > 0.0 || g.friction_viscous > 0.0)
      parts.push_back(fmt::format("friction F_c {:g} {}, F_s {:g} {}, viscous {:g}", g.friction_coulomb,
                                  force, g.friction_static, force, g.friction_viscous / shown));
    if (g.backlash > 0.0) parts.push_back(fmt::format("backlash {:g} {}", g.backlash * shown, length));
    if (g.encoder_resolution > 0.0)
      parts.push_back(fmt::format("encoder count {:g} {}", g.encoder_resolution * shown, length));
    if (g.characteristic_points > 1)
      parts.push_back(fmt::format("static characteristic of {} points", g.characteristic_points));
    drives.push_back(fmt::format("{}", fmt::join(parts, "; ")));
  }
  std::string text;
  const bool alike = std::all_of(drives.begin(), drives.end(), [&](const auto& d) { return d == drives[0]; });
  if (alike && !drives.empty() && !drives[0].empty()) {
    text = "every drive: " + drives[0];
  } else if (!alike) {
    for (std::size_t j = 0; j < drives.size(); ++j)
      if (!drives[j].empty())
        text += fmt::format("{}drive {}: {}", text.empty() ? "" : "; ", j + 1, drives[j]);
  }
  if (design.sample_delay_periods > 0)
    text +=
        fmt::format("{}sample delay {} loop periods", text.empty() ? "" : "; ", design.sample_delay_periods);
  if (!text.empty()) std::cout << "  imperfections   " << text << "\n";
}

void print_servo_summary(const Machine& machine, const pipeline::ServoJob& job,
                         const pipeline::ServoProgramResult& r) {
  const servo::ServoSummary& s = r.summary;
  const bool angular = machine.mechanism->actuators_are_angles();
  const double shown = angular ? 180.0 / 3.14159265358979323846 : 1.0;
  const char* unit = angular ? "deg" : "mm";
  std::cout << fmt::format("{}: {} ticks at {:g} ms, loops every {:g} ms, {} tuning, {} plant{}\n",
                           job.plan_directory, s.ticks, s.period_s * 1e3, s.loop_period_s * 1e3,
                           to_string(machine.servo.tuning), s.coupled ? "coupled" : "decoupled",
                           s.has_machine_dynamics ? "" : " (motors only: no dynamics: section)");
  std::cout << fmt::format(
      "  contour error   max {:.4g} mm (line {}, t = {:.3f} s), rms {:.4g} mm; lag up to "
      "{:.2f} ms\n",
      s.max_contour_error_mm, s.max_contour_line, s.max_contour_time_s, s.rms_contour_error_mm,
      s.max_lag_s * 1e3);
  for (int j = 0; j < s.drives; ++j) {
    const servo::DriveServoSummary& d = s.drive[j];
    const servo::ChannelAnalysis& a = r.analysis[j];
    std::string clamps;
    if (d.error_clamps + d.command_clamps > 0)
      clamps = fmt::format("; limited {}× (e_max {}, u_max {}) first at line {}",
                           d.error_clamps + d.command_clamps, d.error_clamps, d.command_clamps,
                           d.clamp_lines.front());
    std::cout << fmt::format(
        "  drive {}         following error max {:.4g} {} (line {}), rms {:.4g}; peak "
        "command {:.2f} p.u.; coupling {:.2f}{}; speed loop {:.1f} % / PM {:.1f}°, "
        "position loop {:.1f} % / PM {:.1f}° (sampled){}\n",
        j + 1, d.max_following_error * shown, unit, d.max_following_line, d.rms_following_error * shown,
        d.peak_command, d.max_coupling_ratio,
        d.max_coupling_ratio >= servo::kCouplingRatioLimit
            ? fmt::format(" ≥ {} at line {}", servo::kCouplingRatioLimit, d.max_coupling_line)
            : std::string(),
        a.speed_sampled.step.overshoot_pct, a.speed_sampled.margins.phase_margin_deg,
        a.position_sampled.step.overshoot_pct, a.position_sampled.margins.phase_margin_deg, clamps);
  }
  print_imperfections(r.design, angular);
  if (!s.worst_lines.empty()) {
    std::string lines;
    for (const auto& [line, error] : s.worst_lines) lines += fmt::format(" {} ({:.4f})", line, error);
    std::cout << "  worst lines    " << lines << "\n";
  }
  std::cout << fmt::format("  written         {}/servo.csv, servo_bode.csv, servo_summary.json{}\n",
                           job.out_directory.empty() ? job.plan_directory : job.out_directory,
                           job.report_path.empty() ? std::string() : fmt::format("; {}", job.report_path));
}

}  // namespace

void add_servo_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "servo", "a planned run through the drives' servo loops: following and contour error, limits, margins");
  auto job = std::make_shared<pipeline::ServoJob>();
  auto machine_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto decoupled = std::make_shared<bool>(false);
  cmd->add_option("plan", job->plan_directory,
                  "output directory of pkm plan (ticks.h5, or actuators.csv and path.csv)")
      ->required();
  cmd->add_option("--machine", *machine_path, "machine file (YAML) with a servo: section")->required();
  cmd->add_option("--out", job->out_directory,
                  "where to write servo.csv, servo_bode.csv, servo_summary.json "
                  "(default: the plan directory)");
  cmd->add_flag("--decoupled", *decoupled,
                "each drive moves only its own inertia (no coupling through the mechanism)");
  cmd->add_option("--inertia-every", job->inertia_stride,
                  "evaluate the mechanism's inertia every this many servo ticks")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--report", job->report_path,
                  "also write the HTML report of the plan with the servo plots to this file");
  cmd->add_flag("--json", *json, "print the summary as JSON");
  cmd->callback([=, &exit_code] {
    job->coupled = !*decoupled;
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("servo", machine.error());
      return;
    }
    ProgressDisplay progress("servo", "reading the plan");
    job->progress = progress.sink();
    auto result = pipeline::servo_program(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("servo", result.error());
      return;
    }
    if (*json) {
      print_json(result->json);
      return;
    }
    print_servo_summary(*machine, *job, *result);
  });
}

}  // namespace pkm::cli
