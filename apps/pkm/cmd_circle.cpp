// pkm circle --machine M.yaml --out DIR [--radius-mm R] [--feed-mm-min F] [--plane XY|ZX|YZ]
// [--centre X,Y,Z] [--elastic [--load LOAD]] [--json]: the circular test of ISO 230-4 in simulation, through
// the drives' servo loops and their imperfections, on the rigid machine or on the elastic one under a load
// (src/pipeline/circle_test.hpp, docs/servo.md, docs/simulate.md).
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pipeline/circle_test.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

void add_circle_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "circle",
      "the circular test (ISO 230-4) through the drives' servo loops: circular deviation, hysteresis");
  auto job = std::make_shared<pipeline::CircleTestJob>();
  auto machine_path = std::make_shared<std::string>();
  auto centre = std::make_shared<std::vector<double>>(std::vector<double>{0.0, 0.0, 0.0});
  auto json = std::make_shared<bool>(false);
  auto load_text = std::make_shared<std::string>();
  cmd->add_option("--machine", *machine_path, "machine file (YAML) with a servo: section")->required();
  cmd->add_option("--out", job->out_directory,
                  "where to write the plan, the servo run, circle.csv, circle.svg and circle_summary.json")
      ->required();
  cmd->add_option("--radius-mm", job->radius_mm, "the circle's radius")->capture_default_str();
  cmd->add_option("--feed-mm-min", job->feed_mm_min, "the feed along it")->capture_default_str();
  cmd->add_option("--plane", job->plane, "XY (G17), ZX (G18) or YZ (G19)")
      ->check(CLI::IsMember({"XY", "ZX", "YZ"}))
      ->capture_default_str();
  cmd->add_option("--centre", *centre, "the centre in program coordinates, X,Y,Z (mm)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_flag(
      "--elastic", job->elastic,
      "the machine in the loop (pkm simulate): the loops on the elastic machine, not the rigid one");
  cmd->add_option("--load", *load_text,
                  "with --elastic: the process load (key=value pairs as pkm simulate takes them, or @FILE)");
  cmd->add_flag("--json", *json, "print circle_summary.json");
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("circle", machine.error());
      return;
    }
    job->centre_mm = Eigen::Vector3d((*centre)[0], (*centre)[1], (*centre)[2]);
    if (!load_text->empty()) {
      if (!job->elastic) {
        exit_code = report_error(
            "circle",
            make_error(ErrorCode::bad_input, "--load needs --elastic: the rigid machine takes no load"));
        return;
      }
      auto load = statics::parse_load_spec(*load_text);
      if (!load) {
        exit_code = report_error("circle", make_error(load.error().code, "--load: " + load.error().message));
        return;
      }
      job->load = std::move(*load);
    }
    ProgressDisplay progress("circle", "planning the circle");
    job->progress = progress.sink();
    auto result = pipeline::circle_test(*machine, *job);
    progress.finish();
    if (!result) {
      exit_code = report_error("circle", result.error());
      return;
    }
    if (*json) {
      print_json(result->json);
      return;
    }
    std::cout << fmt::format(
        "{}: circle R {:g} mm at {:g} mm/min in {}\n"
        "  circular deviation G  counter-clockwise {:.2f} µm, clockwise {:.2f} µm\n"
        "  hysteresis H          {:.2f} µm\n"
        "  contour error         max {:.4f} mm over the program\n"
        "  written               {}/circle.svg, circle.csv, circle_summary.json, circle.ngc (with the plan "
        "and {})\n",
        machine->source, job->radius_mm, job->feed_mm_min, job->plane,
        result->counter_clockwise.circular_deviation_mm * 1e3, result->clockwise.circular_deviation_mm * 1e3,
        result->hysteresis_mm * 1e3, result->max_contour_error_mm, job->out_directory,
        job->elastic ? "simulate.csv" : "servo.csv");
  });
}

}  // namespace pkm::cli
