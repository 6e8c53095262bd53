// pkm bench kinematics --machine M.yaml [--json]: times IK and FK on this computer.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "machine/kinematics_timing.hpp"
#include "number_options.hpp"

namespace pkm::cli {

void add_bench_command(CLI::App& app, int& exit_code) {
  auto* bench = app.add_subcommand("bench", "time pkm's algorithms on this computer");
  bench->require_subcommand(1);
  auto* cmd = bench->add_subcommand("kinematics", "IK per pose, FK warm along a path and cold from home");
  auto machine_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto options = std::make_shared<KinematicsTimingOptions>();
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  const NumberRange pose_count{1.0, 1e8, true, true, "", true};
  cmd->add_option("--ik-poses", options->ik_poses, "random poses for IK (±20 mm, ±10°)")
      ->capture_default_str()
      ->check(number_in(pose_count));
  cmd->add_option("--path-poses", options->path_poses, "poses along the warm FK path (0.1 mm steps)")
      ->capture_default_str()
      ->check(number_in(pose_count));
  cmd->add_option("--cold-poses", options->cold_poses, "random poses for cold FK from home (±50 mm, ±20°)")
      ->capture_default_str()
      ->check(number_in(pose_count));
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("bench", machine.error());
      return;
    }
    const KinematicsTiming t = time_kinematics(*machine->mechanism, *options);
    if (*json) {
      print_json({{"ik_ns_per_pose", t.ik_ns_per_pose},
                  {"fk_us_per_solve_warm", t.fk_us_per_solve_warm},
                  {"fk_iterations_warm", t.fk_iterations_warm},
                  {"fk_converged_warm", t.fk_converged_warm},
                  {"fk_us_per_solve_cold", t.fk_us_per_solve_cold},
                  {"fk_iterations_cold", t.fk_iterations_cold},
                  {"fk_converged_cold", t.fk_converged_cold}});
    } else {
      std::cout << fmt::format("IK            {:8.1f} ns per pose\n", t.ik_ns_per_pose);
      std::cout << fmt::format("FK warm path  {:8.3f} us per solve, {:.2f} iterations, {:.4f} % converged\n",
                               t.fk_us_per_solve_warm, t.fk_iterations_warm, 100 * t.fk_converged_warm);
      std::cout << fmt::format("FK cold       {:8.3f} us per solve, {:.2f} iterations, {:.4f} % converged\n",
                               t.fk_us_per_solve_cold, t.fk_iterations_cold, 100 * t.fk_converged_cold);
    }
    exit_code = 0;
  });
}

}  // namespace pkm::cli
