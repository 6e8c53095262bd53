// pkm strategies --machine M.yaml --load SPEC --out DIR [--surface ellipsoid:A,B,C] [--centre X,Y,Z]
//   [--depth-mm D] [--step-over-mm S] [--spacing-mm P] [--feed F] [--program FILE ...] [--rate HZ] [--json]:
// the five strategies of Rusanov et al. over an ellipsoid cap and any given programs, planned with the tool's
// deflection under the load and ranked by the error along the surface normal (pipeline/strategy_comparison,
// docs/strategies.md). Prints the ranking; writes the table, the plot and every run into DIR.
#include <fmt/format.h>

#include <iostream>
#include <numbers>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/pose_input.hpp"
#include "number_options.hpp"
#include "path/ellipsoid_cap.hpp"
#include "pipeline/strategy_comparison.hpp"
#include "progress_display.hpp"
#include "statics/load_model.hpp"

namespace pkm::cli {
namespace {

struct StrategiesArguments {
  std::string machine_path, out_dir, load, surface = "ellipsoid:100,80,40", centre;
  double depth_mm = 4.0;
  std::vector<std::string> programs;
  bool json = false;
};

// "ellipsoid:A,B,C" → the cap's semi-axes (the only kind so far).
Result<Eigen::Vector3d> strategies_surface_axes(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  if (kind != "ellipsoid") {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("--surface: unknown surface kind '{}' (known: ellipsoid:A,B,C in mm)", kind));
  }
  if (colon == std::string::npos)
    return make_error(ErrorCode::bad_input, "--surface: ellipsoid needs its semi-axes: ellipsoid:A,B,C (mm)");
  auto numbers = parse_number_list(std::string_view(text).substr(colon + 1), "--surface");
  if (!numbers) return numbers.error();
  if (numbers->size() != 3) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("--surface: ellipsoid takes 3 semi-axes A,B,C (mm), got {}", numbers->size()));
  }
  return Eigen::Vector3d((*numbers)[0], (*numbers)[1], (*numbers)[2]);
}

Result<pipeline::StrategyComparisonJob> strategies_job(const StrategiesArguments& a, bool generate,
                                                       pipeline::StrategyComparisonJob job) {
  if (generate) {
    auto axes = strategies_surface_axes(a.surface);
    if (!axes) return axes.error();
    path::EllipsoidCap cap;
    cap.semi_axes_mm = *axes;
    cap.depth_mm = a.depth_mm;
    cap.centre_mm = Eigen::Vector3d(0.0, 0.0, -axes->z());  // the cap's top at program zero
    if (!a.centre.empty()) {
      auto centre = parse_number_list(a.centre, "--centre");
      if (!centre) return centre.error();
      if (centre->size() != 3)
        return make_error(ErrorCode::bad_input,
                          fmt::format("--centre: expected 3 numbers x,y,z (mm), got {}", centre->size()));
      cap.centre_mm = Eigen::Vector3d((*centre)[0], (*centre)[1], (*centre)[2]);
    }
    // The messages name the semi-axis, the centre or the depth themselves.
    if (Status valid = path::validate_ellipsoid_cap(cap); !valid) return valid.error();
    job.surface = cap;
  }
  auto load = statics::parse_load_spec(a.load);
  if (!load) return make_error(load.error().code, "--load: " + load.error().message);
  for (const std::string& program : a.programs) {
    if (Status lines = statics::check_load_lines(*load, program); !lines)
      return make_error(lines.error().code, "--load: " + lines.error().message);
  }
  job.load = std::move(*load);
  job.programs = a.programs;
  job.out_directory = a.out_dir;
  return job;
}

nlohmann::json strategies_json(const pipeline::StrategyComparison& comparison, const std::string& out_dir) {
  nlohmann::json rows = nlohmann::json::array();
  for (const pipeline::StrategyScore& s : comparison.ranking) {
    rows.push_back({{"rank", s.rank},
                    {"strategy", s.name},
                    {"program", s.program_path},
                    {"points", s.points},
                    {"path_length_mm", s.path_length_mm},
                    {"time_s", s.cutting_time_s},
                    {"rms_normal_um", s.rms_normal_mm * 1e3},
                    {"max_normal_um", s.max_normal_mm * 1e3},
                    {"max_line", s.max_normal_line}});
  }
  return {{"criterion", std::string(pipeline::kStrategyCriterion)}, {"strategies", rows}, {"out", out_dir}};
}

void print_strategies_table(const pipeline::StrategyComparison& comparison,
                            const pipeline::StrategyComparisonJob& job, const std::string& machine_name,
                            const StrategiesArguments& a) {
  if (job.surface) {
    const path::EllipsoidCap& cap = *job.surface;
    const Eigen::Vector2d outline = path::cap_outline_semi_axes_mm(cap);
    std::cout << fmt::format(
        "{}: ellipsoid {} × {} × {} mm, cap {} mm deep ({:.1f} × {:.1f} mm, tilt ≤ {:.1f}°), step-over {} "
        "mm, "
        "spacing {} mm, feed {} mm/min, load {}\n",
        machine_name, cap.semi_axes_mm.x(), cap.semi_axes_mm.y(), cap.semi_axes_mm.z(), cap.depth_mm,
        2 * outline.x(), 2 * outline.y(), path::cap_max_tilt_rad(cap) * 180.0 / std::numbers::pi,
        job.strategy.step_over_mm, job.strategy.spacing_mm, job.feed_mm_min, a.load);
  } else {
    std::cout << fmt::format("{}: load {}\n", machine_name, a.load);
  }
  std::cout << fmt::format("ranked by the {}\n", pipeline::kStrategyCriterion);
  std::cout << fmt::format("{:>4}  {:<14} {:>7} {:>9} {:>8} {:>10} {:>10} {:>6}\n", "rank", "strategy",
                           "points", "path mm", "time s", "rms µm", "max µm", "line");
  for (const pipeline::StrategyScore& s : comparison.ranking) {
    std::cout << fmt::format("{:>4}  {:<14} {:>7} {:>9.1f} {:>8.2f} {:>10.4f} {:>10.4f} {:>6}\n", s.rank,
                             s.name, s.points, s.path_length_mm, s.cutting_time_s, s.rms_normal_mm * 1e3,
                             s.max_normal_mm * 1e3, s.max_normal_line);
  }
  std::cout << fmt::format(
      "written           {}/strategies.csv, strategies.svg and a run folder per strategy\n", a.out_dir);
}

}  // namespace

void add_strategies_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "strategies",
      "compare machining strategies (zigzag, meridians, parallels, contour, contour loop) over an ellipsoid "
      "cap, and any CL files, by the surface error the tool's deflection under load leaves");
  auto a = std::make_shared<StrategiesArguments>();
  auto job = std::make_shared<pipeline::StrategyComparisonJob>();
  cmd->add_option("--machine", a->machine_path, "machine file (YAML) with strut stiffness")->required();
  cmd->add_option("--load", a->load,
                  "cutting load: key=value list (tangential, normal, axial, cutter_radius, contact, force, "
                  "moment) or @FILE.yaml (docs/statics.md)")
      ->required();
  cmd->add_option("--out", a->out_dir, "directory for strategies.csv, strategies.svg and the runs")
      ->required();
  auto* surface = cmd->add_option("--surface", a->surface, "the surface: ellipsoid:A,B,C (semi-axes, mm)")
                      ->capture_default_str();
  cmd->add_option("--centre", a->centre,
                  "the ellipsoid's centre x,y,z, mm, program coordinates (default 0,0,-C)");
  cmd->add_option("--depth-mm", a->depth_mm, "the cap: the surface within this depth below its top, mm (< C)")
      ->capture_default_str()
      ->check(number_in({0.0, 1e5, false, true, "mm"}));
  cmd->add_option("--step-over-mm", job->strategy.step_over_mm,
                  "largest distance between passes on the surface, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 1e4, false, true, "mm"}));
  cmd->add_option("--spacing-mm", job->strategy.spacing_mm,
                  "largest distance between points along a pass, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 1e4, false, true, "mm"}));
  cmd->add_option("--feed", job->feed_mm_min, "feed of the generated programs, mm/min")
      ->capture_default_str()
      ->check(number_in({0.0, 1e6, false, true, "mm/min"}));
  cmd->add_option("--program", a->programs,
                  "also rank this part program (CL data with the tool axis on the normal, or G-code); "
                  "repeatable; without --surface only the programs given are ranked");
  cmd->add_option("--rate", job->plan.rate_hz, "servo rate, Hz")
      ->capture_default_str()
      ->check(number_in({1.0, 100000.0, true, true, "Hz"}));
  cmd->add_flag("--json", a->json, "print the ranking as JSON");
  cmd->callback([a, job, surface, &exit_code] {
    const bool generate = surface->count() > 0 || a->programs.empty();
    auto prepared = strategies_job(*a, generate, *job);
    if (!prepared) {
      exit_code = report_error("strategies", prepared.error());
      return;
    }
    auto machine = load_machine_or_report(a->machine_path);
    if (!machine) {
      exit_code = report_error("strategies", machine.error());
      return;
    }
    ProgressDisplay progress("strategies", "planning and analysing each strategy");
    prepared->progress = progress.sink();
    auto comparison = pipeline::compare_strategies(*machine, *prepared);
    progress.finish();
    if (!comparison) {
      exit_code = report_error("strategies", comparison.error());
      return;
    }
    if (a->json) {
      print_json(strategies_json(*comparison, a->out_dir));
      return;
    }
    print_strategies_table(*comparison, *prepared, machine->name, *a);
  });
}

}  // namespace pkm::cli
