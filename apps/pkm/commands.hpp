#pragma once
// One function per subcommand; each adds its options to the app and sets `exit_code` when it runs.
#include <CLI/CLI.hpp>

namespace pkm::cli {

void add_ik_command(CLI::App& app, int& exit_code);
void add_fk_command(CLI::App& app, int& exit_code);
void add_check_command(CLI::App& app, int& exit_code);
void add_jacobian_command(CLI::App& app, int& exit_code);
void add_modes_command(CLI::App& app, int& exit_code);
void add_modes_margin_command(CLI::App& app, int& exit_code);
void add_compliance_command(CLI::App& app, int& exit_code);
void add_stiffness_command(CLI::App& app, int& exit_code);
void add_bench_command(CLI::App& app, int& exit_code);
void add_demo_command(CLI::App& app, int& exit_code);
void add_interpret_command(CLI::App& app, int& exit_code);
void add_plan_command(CLI::App& app, int& exit_code);
void add_optimize_command(CLI::App& app, int& exit_code);
void add_play_command(CLI::App& app, int& exit_code);
void add_interpolate_command(CLI::App& app, int& exit_code);
void add_report_command(CLI::App& app, int& exit_code);
void add_strategies_command(CLI::App& app, int& exit_code);
void add_workspace_command(CLI::App& app, int& exit_code);
void add_servo_command(CLI::App& app, int& exit_code);
void add_circle_command(CLI::App& app, int& exit_code);
void add_spif_command(CLI::App& app, int& exit_code);
void add_simulate_command(CLI::App& app, int& exit_code);
void add_calibrate_command(CLI::App& app, int& exit_code);
void add_linuxcnc_command(CLI::App& app, int& exit_code);

}  // namespace pkm::cli
