// pkm ik --machine M.yaml --pose x,y,z,a1,a2,a3 [--json]: actuator positions of a pose.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/pose_input.hpp"
#include "pose_reach.hpp"

namespace pkm::cli {

void add_ik_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("ik", "inverse kinematics: actuator positions of a pose");
  auto machine_path = std::make_shared<std::string>();
  auto pose_text = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  cmd->add_option("--pose", *pose_text,
                  "x,y,z (mm) and three angles (deg, the machine's convention); planar: x,y[,phi]")
      ->required()
      ->allow_extra_args(false);
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("ik", machine.error());
      return;
    }
    const Mechanism& mech = *machine->mechanism;
    auto values = parse_number_list(*pose_text, "--pose");
    if (!values) {
      exit_code = report_error("ik", values.error());
      return;
    }
    auto pose = pose_from_user(mech, *values, "--pose");
    if (!pose) {
      exit_code = report_error("ik", pose.error());
      return;
    }
    if (Status reachable = pose_within_actuator_range(*machine, *pose); !reachable) {
      exit_code = report_error("ik", reachable.error());
      return;
    }
    auto q = mech.inverse(*pose);
    const auto actuators = user_from_actuators(mech, *q);
    const auto full_pose = user_from_pose(mech, *pose);
    if (*json) {
      print_json({{"actuators", actuators}, {"unit", actuator_unit_name(mech)}, {"pose", full_pose}});
    } else {
      std::cout << fmt::format("{:.10f}", fmt::join(actuators, " ")) << "  (" << actuator_unit_name(mech)
                << ")\n";
    }
    exit_code = 0;
  });
}

}  // namespace pkm::cli
