// pkm linuxcnc config --machine M.yaml --out DIR [--kinematics pkmkins|genhexkins|trivkins]
// [--display PROGRAM] [--homing at-home|switches] [--drives steps|servo] [--execute] [--json]: a simulated
// LinuxCNC configuration of the machine, with pkm's executor when --execute (pipeline/linuxcnc_config.hpp,
// docs/linuxcnc.md).
// pkm linuxcnc stream PROGRAM --machine M.yaml [--to -|FILE] [--out DIR] [--period-ms H] [--step-mm D]: the
// program planned for execution and interpolated to whole steps, streamed period by period for pkm's HAL
// component (pipeline/execution_stream_job.hpp).
#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pipeline/execution_stream_job.hpp"
#include "pipeline/linuxcnc_config.hpp"
#include "pipeline/linuxcnc_launch.hpp"
#include "program_options.hpp"
#include "progress_display.hpp"

namespace pkm::cli {

namespace {

struct StreamArguments {
  std::string program, machine, to = "-", out;
  ProgramArguments program_options;
  double period_ms = 1.0, step_mm = 0.001;
};

void add_stream_command(CLI::App& linuxcnc, int& exit_code) {
  auto* cmd = linuxcnc.add_subcommand(
      "stream", "plan a program for execution and stream its drive steps to pkm's HAL component pkmexec");
  auto args = std::make_shared<StreamArguments>();
  cmd->add_option("program", args->program, "part program: G-code, or CL data")->required();
  cmd->add_option("--machine", args->machine, "machine file (YAML)")->required();
  cmd->add_option("--to", args->to,
                  "where the stream goes: - (standard output, for linuxcnc/pkm_feed.py) or a file")
      ->capture_default_str();
  cmd->add_option("--out", args->out,
                  "also write the interpolation's steps.csv, steps.bin, contour.csv and summary.json here");
  auto* period =
      cmd->add_option("--period-ms", args->period_ms, "servo period, ms (default drives.period_ms, else 1)")
          ->check(CLI::Range(0.1, 20.0));
  auto* step =
      cmd->add_option("--step-mm", args->step_mm, "drive resolution, mm per step (default drives.step_mm)")
          ->check(CLI::PositiveNumber);
  add_program_options(*cmd, args->program_options);
  cmd->callback([args, period, step, &exit_code] {
    auto machine = load_machine_or_report(args->machine);
    if (!machine) {
      exit_code = report_error("linuxcnc stream", machine.error());
      return;
    }
    pipeline::ExecutionStreamJob job;
    job.program_path = args->program;
    job.program_options = args->program_options.options();
    job.target = args->to;
    job.out_directory = args->out;
    if (period->count() > 0) job.period_ms = args->period_ms;
    if (step->count() > 0) job.step = args->step_mm;
    ProgressDisplay progress("linuxcnc stream", "reading the program");
    job.progress = progress.sink();
    auto result = pipeline::stream_for_execution(std::move(*machine), job);
    progress.finish();
    if (!result) {
      exit_code = report_error("linuxcnc stream", result.error());
      return;
    }
    // Standard output may be the stream itself: the account goes to standard error.
    std::cerr << fmt::format(
        "pkm linuxcnc stream: {} periods, contour error max {:.6f} mm; planned within "
        "{:.6g}/s and {:.6g}/s² of the drives' limits for overrides up to {:.0f} %\n",
        result->summary.periods, result->summary.contour.max_error_mm, result->headroom.nominal.speed,
        result->headroom.nominal.accel, 100.0 * result->headroom.max_override);
  });
}

}  // namespace

void add_linuxcnc_command(CLI::App& app, int& exit_code) {
  auto* linuxcnc = app.add_subcommand("linuxcnc", "run the machine on LinuxCNC (docs/linuxcnc.md)");
  linuxcnc->require_subcommand(1);
  add_stream_command(*linuxcnc, exit_code);
  auto* cmd = linuxcnc->add_subcommand("config", "write a simulated LinuxCNC configuration for a machine");
  auto machine_path = std::make_shared<std::string>();
  auto options = std::make_shared<LinuxcncConfigOptions>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  cmd->add_option("--out", options->out_directory, "directory to write machine.ini and its files into")
      ->required();
  auto kinematics = std::make_shared<std::string>("pkmkins");
  cmd->add_option("--kinematics", *kinematics,
                  "kinematics module: pkmkins (pkm's); LinuxCNC's genhexkins for comparison, or its trivkins "
                  "(joints = coordinates, no kinematics: a timing baseline)")
      ->check(CLI::IsMember({"pkmkins", "genhexkins", "trivkins"}))
      ->capture_default_str();
  cmd->add_option("--display", options->display,
                  "LinuxCNC user interface ([DISPLAY] DISPLAY); without an X display linuxcncrsh (LinuxCNC's "
                  "text interface, port 5007) or pkm's linuxcnc/headless_run.py (runs one program)")
      ->capture_default_str();
  auto homing = std::make_shared<std::string>("at-home");
  cmd->add_option("--homing", *homing,
                  "at-home (the joints home at once where home puts them) or switches (each strut down to a "
                  "lower boundary switch, back off it slowly: simulated switches in the HAL file)")
      ->check(CLI::IsMember({"at-home", "switches"}))
      ->capture_default_str();
  auto drives = std::make_shared<std::string>("steps");
  cmd->add_option("--drives", *drives,
                  "the drives simulated (and shown as real examples): steps (each where it is commanded) or "
                  "servo (a position loop on a motor)")
      ->check(CLI::IsMember({"steps", "servo"}))
      ->capture_default_str();
  cmd->add_flag("--execute", options->execute,
                "also load pkm's executor pkmexec: programs planned by `pkm linuxcnc stream` run with their "
                "exact drive steps, LinuxCNC homes, jogs and runs G-code in between");
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("linuxcnc config", machine.error());
      return;
    }
    options->kinematics = *kinematics == "genhexkins" ? LinuxcncKinematics::genhexkins
                          : *kinematics == "trivkins" ? LinuxcncKinematics::trivkins
                                                      : LinuxcncKinematics::pkmkins;
    options->homing = *homing == "switches" ? LinuxcncHoming::switches : LinuxcncHoming::at_home;
    options->drives = *drives == "servo" ? LinuxcncDrives::servo : LinuxcncDrives::steps;
    auto written = write_linuxcnc_config(*machine, *options);
    if (!written) {
      exit_code = report_error("linuxcnc config", written.error());
      return;
    }
    if (*json) {
      print_json({{"directory", options->out_directory},
                  {"files", written->files},
                  {"kinematics", std::string(to_string(options->kinematics))},
                  {"coordinates", written->coordinates},
                  {"home_joints", written->home_joints},
                  {"servo_period_ns", written->servo_period_ns},
                  {"drives", *drives},
                  {"execute", options->execute}});
      return;
    }
    std::cout << fmt::format(
        "wrote {}/machine.ini ({}, {} joints, coordinates {}, servo period {} ns, {} drives{})\n",
        options->out_directory, to_string(options->kinematics), written->home_joints.size(),
        written->coordinates, written->servo_period_ns, *drives == "servo" ? "servo" : "step",
        options->execute ? ", pkm's executor pkmexec" : "");
    // As it would run here: as root rtapi_app needs a user and a socket path; a GUI needs an X display.
    const bool as_root = ::geteuid() == 0;
    const char* x_display = std::getenv("DISPLAY");
    std::cout << "run it with: " << linuxcnc_start_command(options->out_directory, as_root);
    if (options->kinematics == LinuxcncKinematics::pkmkins || options->execute)
      std::cout << fmt::format(" ({} installed in LinuxCNC's modules: make linuxcnc)",
                               options->kinematics == LinuxcncKinematics::pkmkins
                                   ? (options->execute ? "pkmkins.so and pkmexec.so" : "pkmkins.so")
                                   : "pkmexec.so");
    std::cout << "\n";
    for (const std::string& problem : linuxcnc_start_problems(
             options->out_directory, options->display, as_root, x_display != nullptr && x_display[0] != '\0'))
      std::cerr << "pkm linuxcnc config: warning: " << problem << "\n";
  });
}

}  // namespace pkm::cli
