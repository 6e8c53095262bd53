// pkm: plans, executes and analyses motion for parallel-kinematic machines. Each subcommand lives in
// cmd_*.cpp.
#include <CLI/CLI.hpp>
#include <string>

#include "command_groups.hpp"
#include "commands.hpp"
#include "io/output_cleanup.hpp"
#include "io/version.hpp"
#include "number_options.hpp"
#include "output_options.hpp"
#include "progress_display.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "pkm: kinematics and motion for parallel-kinematic machines (hexapods, tripods, tricepts, glides)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pkm " + std::string(pkm::pkm_version()), "print pkm's version and exit");
  int exit_code = 0;
  // In the order of `pkm --help`'s groups (command_groups.cpp): CLI11 lists groups as it first meets them.
  pkm::cli::add_plan_command(app, exit_code);
  pkm::cli::add_interpret_command(app, exit_code);
  pkm::cli::add_interpolate_command(app, exit_code);
  pkm::cli::add_play_command(app, exit_code);
  pkm::cli::add_servo_command(app, exit_code);
  pkm::cli::add_optimize_command(app, exit_code);
  pkm::cli::add_report_command(app, exit_code);
  pkm::cli::add_stiffness_command(app, exit_code);
  pkm::cli::add_compliance_command(app, exit_code);
  pkm::cli::add_modes_command(app, exit_code);
  pkm::cli::add_modes_margin_command(app, exit_code);
  pkm::cli::add_workspace_command(app, exit_code);
  pkm::cli::add_strategies_command(app, exit_code);
  pkm::cli::add_jacobian_command(app, exit_code);
  pkm::cli::add_circle_command(app, exit_code);
  pkm::cli::add_spif_command(app, exit_code);
  pkm::cli::add_simulate_command(app, exit_code);
  pkm::cli::add_check_command(app, exit_code);
  pkm::cli::add_ik_command(app, exit_code);
  pkm::cli::add_fk_command(app, exit_code);
  pkm::cli::add_demo_command(app, exit_code);
  pkm::cli::add_linuxcnc_command(app, exit_code);
  pkm::cli::add_calibrate_command(app, exit_code);
  pkm::cli::add_bench_command(app, exit_code);
  pkm::cli::group_commands(app);
  pkm::cli::add_output_options(app);
  pkm::cli::add_progress_options(app);
  // A stopped run removes its staging folder and temporaries and exits 130 (SIGINT) or 143 (SIGTERM).
  pkm::install_output_cleanup_handlers();
  if (auto refused = pkm::cli::refuse_unknown_command(app, argc, argv)) return *refused;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return pkm::cli::exit_for_parse_error(app, e);
  }
  return exit_code;
}
