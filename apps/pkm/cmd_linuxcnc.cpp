// pkm linuxcnc config --machine M.yaml --out DIR [--kinematics pkmkins|genhexkins] [--display PROGRAM]
// [--json]: a simulated LinuxCNC configuration of the machine (pipeline/linuxcnc_config.hpp,
// docs/linuxcnc.md).
#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pipeline/linuxcnc_config.hpp"
#include "pipeline/linuxcnc_launch.hpp"

namespace pkm::cli {

void add_linuxcnc_command(CLI::App& app, int& exit_code) {
  auto* linuxcnc = app.add_subcommand("linuxcnc", "run the machine on LinuxCNC (docs/linuxcnc.md)");
  linuxcnc->require_subcommand(1);
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
                  {"servo_period_ns", written->servo_period_ns}});
      return;
    }
    std::cout << fmt::format("wrote {}/machine.ini ({}, {} joints, coordinates {}, servo period {} ns)\n",
                             options->out_directory, to_string(options->kinematics),
                             written->home_joints.size(), written->coordinates, written->servo_period_ns);
    // As it would run here: as root rtapi_app needs a user and a socket path; a GUI needs an X display.
    const bool as_root = ::geteuid() == 0;
    const char* x_display = std::getenv("DISPLAY");
    std::cout << "run it with: " << linuxcnc_start_command(options->out_directory, as_root);
    if (options->kinematics == LinuxcncKinematics::pkmkins)
      std::cout << " (pkmkins.so installed in LinuxCNC's modules: make linuxcnc)";
    std::cout << "\n";
    for (const std::string& problem : linuxcnc_start_problems(
             options->out_directory, options->display, as_root, x_display != nullptr && x_display[0] != '\0'))
      std::cerr << "pkm linuxcnc config: warning: " << problem << "\n";
  });
}

}  // namespace pkm::cli
