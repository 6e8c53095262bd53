// pkm spif program --out FILE.ngc [--radius-mm R] [--radius-step-mm D] [--planes N | --profile CSV]
//   [--step-down-mm S]
//   [--direction ccw|cw] [--depth down|up] [--z1-mm Z] [--centre X,Y] [--feed-mm-min F] [--path planes|helix]
// pkm spif placement PROGRAM --machine M --z1 FROM:TO:STEP|Z,Z,... [--load SPEC] [--step-mm S]
//   [--law L [--bounds LO,HI[,...]]] --out DIR [--json]
// Single point incremental forming (Smirnov 2019, §3.8.1): the forming path, and where to put the sheet so
// that the drives spend least energy on it (docs/spif.md).
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/atomic_file.hpp"
#include "io/output_set.hpp"
#include "io/spif_profile_file.hpp"
#include "number_options.hpp"
#include "pipeline/spif_placement_job.hpp"
#include "program/spif_path.hpp"
#include "program_options.hpp"
#include "progress_display.hpp"
#include "redundancy_options.hpp"

namespace pkm::cli {
namespace {

void add_program_subcommand(CLI::App& spif, int& exit_code) {
  auto* cmd =
      spif.add_subcommand("program", "write a forming path: circles in planes stepped into the sheet");
  auto options = std::make_shared<program::SpifPathOptions>();
  auto out = std::make_shared<std::string>();
  auto direction = std::make_shared<std::string>("ccw");
  auto depth = std::make_shared<std::string>("down");
  auto kind = std::make_shared<std::string>("planes");
  auto centre = std::make_shared<std::vector<double>>(std::vector<double>{0.0, 0.0});
  cmd->add_option("--out", *out, "the program (.ngc)")->required();
  auto profile = std::make_shared<std::string>();
  auto* radius =
      cmd->add_option("--radius-mm", options->radius_mm, "the first circle's radius")->capture_default_str();
  auto* radius_step =
      cmd->add_option("--radius-step-mm", options->radius_step_mm, "each next circle this much smaller")
          ->capture_default_str();
  auto* planes = cmd->add_option("--planes", options->planes, "how many planes")->capture_default_str();
  cmd->add_option(
         "--profile", *profile,
         "an axisymmetric wall instead of the cone: CSV depth_mm,radius_mm from depth 0 (docs/spif.md)")
      ->excludes(radius)
      ->excludes(radius_step)
      ->excludes(planes);
  cmd->add_option("--step-down-mm", options->step_down_mm, "between planes")->capture_default_str();
  cmd->add_option("--direction", *direction, "ccw (G3, positive phi) | cw (G2)")
      ->check(CLI::IsMember({"ccw", "cw"}))
      ->capture_default_str();
  cmd->add_option("--depth", *depth, "the planes step along -Z (down) or +Z (up: a tool pointing up)")
      ->check(CLI::IsMember({"down", "up"}))
      ->capture_default_str();
  cmd->add_option("--z1-mm", options->z1_mm, "the first plane's Z")->capture_default_str();
  cmd->add_option("--centre", *centre, "the circles' centre X,Y (mm)")->delimiter(',')->expected(2);
  cmd->add_option("--feed-mm-min", options->feed_mm_min, "the forming feed")->capture_default_str();
  cmd->add_option("--path", *kind, "planes (a circle per plane) | helix (each turn a helix down)")
      ->check(CLI::IsMember({"planes", "helix"}))
      ->capture_default_str();
  cmd->callback([=, &exit_code] {
    options->counter_clockwise = *direction == "ccw";
    options->depth_up = *depth == "up";
    options->kind = *kind == "helix" ? program::SpifPathKind::helix : program::SpifPathKind::planes;
    options->centre_mm = Eigen::Vector2d((*centre)[0], (*centre)[1]);
    if (!profile->empty()) {
      auto rows = read_spif_profile(*profile);
      if (!rows) {
        exit_code = report_error("spif program", rows.error());
        return;
      }
      options->profile = std::move(*rows);
    }
    auto text = program::spif_program_text(*options);
    if (!text) {
      exit_code = report_error("spif program", text.error());
      return;
    }
    OutputSet outputs{"spif program"};
    auto staged = outputs.stage_file(*out);
    Status written = staged ? write_file_atomically(*staged, *text) : Status(staged.error());
    if (written) written = outputs.commit();
    if (!written) {
      exit_code = report_error("spif program", written.error());
      return;
    }
    // The program's first line says what it holds.
    std::cout << fmt::format("written {}: {}\n", *out, text->substr(2, text->find(" )") - 2));
  });
}

// --z1 FROM:TO:STEP or a comma-separated list of heights (mm).
Result<std::vector<double>> parse_heights(const std::string& text) {
  auto number = [](std::string_view part, double& value) {
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
    return error == std::errc() && end == part.data() + part.size() && std::isfinite(value) &&
           std::abs(value) <= 1e5;
  };
  auto bad = [&text] {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--z1 {}: expected FROM:TO:STEP (e.g. 300:700:50) or heights Z,Z,... in mm "
                                  "(within ±1e5)",
                                  text));
  };
  std::vector<std::string_view> parts;
  const char separator = text.find(':') != std::string::npos ? ':' : ',';
  for (std::size_t from = 0;;) {
    const std::size_t at = text.find(separator, from);
    parts.push_back(std::string_view(text).substr(from, at == std::string::npos ? at : at - from));
    if (at == std::string::npos) break;
    from = at + 1;
  }
  std::vector<double> values(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (!number(parts[i], values[i])) return bad();
  if (separator == ',') return values;
  if (values.size() != 3 || !(values[2] > 0.0) || !(values[1] >= values[0]) ||
      (values[1] - values[0]) / values[2] > 1000.0)
    return bad();
  std::vector<double> heights;
  // Each height from the first and its index (a running sum would drift off TO and print 300.00000000001).
  const int count = static_cast<int>(std::floor((values[1] - values[0]) / values[2] + 1e-9)) + 1;
  for (int i = 0; i < count; ++i) heights.push_back(values[0] + i * values[2]);
  return heights;
}

void print_placement(const nlohmann::json& s, const std::string& program, const std::string& out) {
  std::cout << fmt::format("{}: drive energy at {} heights of the first plane\n", program,
                           s["placements"].size());
  for (const auto& row : s["placements"]) {
    if (!row["feasible"].get<bool>()) {
      std::cout << fmt::format("  Z{:<8g} out of reach from line {}\n", row["z1_mm"].get<double>(),
                               row["first_infeasible_line"].get<int>());
      continue;
    }
    const std::string law = row.contains("law_energy_J")
                                ? fmt::format(", by the law {:.3f} J", row["law_energy_J"].get<double>())
                                : std::string();
    std::cout << fmt::format("  Z{:<8g} {:12.3f} J{}   (required work {:.3f} J, peak force {:.1f} N)\n",
                             row["z1_mm"].get<double>(), row["energy_J"].get<double>(), law,
                             row["required_work_J"].get<double>(), row["peak_force_N"].get<double>());
  }
  std::cout << fmt::format(
      "  least at Z{:g}, most at Z{:g}: {:.2f} times as much\n  written     {}/placement.csv, placement.svg, "
      "summary.json\n",
      s["lowest_energy"]["z1_mm"].get<double>(), s["highest_energy"]["z1_mm"].get<double>(),
      s["energy_ratio"].get<double>(), out);
}

void add_placement_subcommand(CLI::App& spif, int& exit_code) {
  auto* cmd = spif.add_subcommand(
      "placement", "the drive energy of a forming program at a range of heights of its first plane");
  auto job = std::make_shared<pipeline::SpifPlacementJob>();
  auto machine_path = std::make_shared<std::string>();
  auto heights = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto program_arguments = std::make_shared<ProgramArguments>();
  cmd->add_option("program", job->program_path, "the forming program: G-code or CL data")->required();
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  cmd->add_option("--z1", *heights, "heights of the first plane: FROM:TO:STEP or Z,Z,... (mm)")->required();
  cmd->add_option("--load", job->load_text,
                  "the forming load: key=value list (axial, tangential, normal, ...) or @FILE.yaml "
                  "(docs/statics.md)");
  auto law = std::make_shared<std::string>();
  auto bounds = std::make_shared<std::string>();
  cmd->add_option("--law", *law,
                  "also the energy with the angles chosen by this law (energy, the seeds'; increment, force, "
                  "rotation, potential), returned to the programmed ones at every plane");
  cmd->add_option("--bounds", *bounds,
                  "with --law: LO,HI of every angle or LO,HI,LO,HI,LO,HI of each (degrees; the seeds: "
                  "-5,5,-5,5,-20,20)");
  cmd->add_option("--step-mm", job->placement.step_mm, "path step the energy is summed over")
      ->capture_default_str()
      ->check(number_in({0.0, 1000.0, false, true, "mm"}));
  cmd->add_option("--out", job->out_directory, "where to write placement.csv, placement.svg, summary.json")
      ->required();
  cmd->add_flag("--json", *json, "print summary.json");
  add_program_options(*cmd, *program_arguments);
  cmd->callback([=, &exit_code] {
    auto z1 = parse_heights(*heights);
    if (!z1) {
      exit_code = report_error("spif placement", z1.error());
      return;
    }
    job->placement.z1_mm = std::move(*z1);
    if (!law->empty()) {
      const auto chosen = redundancy::law_from_string(*law);
      if (!chosen) {
        exit_code = report_error(
            "spif placement",
            make_error(
                ErrorCode::bad_input,
                fmt::format("--law {}: expected energy, increment, force, rotation or potential", *law)));
        return;
      }
      job->placement.law = *chosen;
    }
    if (!bounds->empty()) {
      auto parsed = parse_bounds(*bounds);
      if (!parsed || law->empty()) {
        exit_code =
            report_error("spif placement",
                         parsed ? make_error(ErrorCode::bad_input, "--bounds needs --law") : parsed.error());
        return;
      }
      job->placement.law_bounds_deg = std::move(*parsed);
    }
    if (!job->load_text.empty()) {
      auto loads = statics::parse_load_spec(job->load_text);
      if (!loads) {
        exit_code = report_error("spif placement",
                                 make_error(loads.error().code, "--load: " + loads.error().message));
        return;
      }
      job->placement.loads = std::move(*loads);
    }
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("spif placement", machine.error());
      return;
    }
    job->program_options = program_arguments->options();
    ProgressDisplay progress("spif placement", "reading the program");
    job->progress = progress.sink();
    auto result = pipeline::run_spif_placement_job(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("spif placement", result.error());
      return;
    }
    const nlohmann::json& s = result->summary;
    if (*json) {
      print_json(s);
      return;
    }
    print_placement(s, job->program_path, job->out_directory);
  });
}

}  // namespace

void add_spif_command(CLI::App& app, int& exit_code) {
  auto* spif = app.add_subcommand(
      "spif", "single point incremental forming: forming paths and where to place the sheet (docs/spif.md)");
  spif->require_subcommand(1);
  add_program_subcommand(*spif, exit_code);
  add_placement_subcommand(*spif, exit_code);
}

}  // namespace pkm::cli
