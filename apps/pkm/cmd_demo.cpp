// pkm demo --machine M.yaml: the kinematics demo that `make run` shows — a table of poses around home, their
// actuator positions, and the error of forward kinematics recovering each pose from those positions.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/units.hpp"
#include "io/pose_input.hpp"

namespace pkm::cli {

void add_demo_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("demo", "kinematics demo: poses, actuator positions, FK round-trip errors");
  auto machine_path = std::make_shared<std::string>();
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("demo", machine.error());
      return;
    }
    const Mechanism& mech = *machine->mechanism;
    const PoseVector home = vector_from_pose(mech.convention(), mech.home());
    const AxisMask mask = mech.controlled_axes();
    // Home, then ±40 mm along each controlled translation and ±8° about each controlled angle.
    std::vector<PoseVector> targets = {home};
    for (int axis = 0; axis < 6; ++axis) {
      if (!mask.controlled[axis]) continue;
      for (double sign : {-1.0, 1.0}) {
        PoseVector c = home;
        c[axis] += sign * (axis < 3 ? 40.0 : rad_from_deg(8.0));
        targets.push_back(c);
      }
    }
    const auto names = pose_coordinate_names(mech);
    std::cout << fmt::format("{} ({}), {} convention, actuators in {}\n\n", machine->name,
                             to_string(mech.type()), to_string(mech.convention()), actuator_unit_name(mech));
    std::cout << fmt::format("{:<58} {:<}  {:>12} {:>12} {:>5}\n", "pose (mm, deg)", "actuators", "FK err mm",
                             "FK err deg", "iter");
    int failures = 0;
    for (const PoseVector& c : targets) {
      auto pose = mech.complete_pose(pose_from_vector(mech.convention(), c));
      if (!pose) continue;
      const auto shown = user_from_pose(mech, *pose);
      auto q = mech.inverse(*pose);
      std::string pose_text = fmt::format("{:.2f}", fmt::join(shown, " "));
      if (!q) {
        std::cout << fmt::format("{:<58} unreachable: {}\n", pose_text, q.error().message);
        continue;
      }
      const std::string range_note = check_actuator_range(*machine, *q) ? "" : "  (outside actuator range)";
      auto fk = mech.forward(*q, mech.home());
      const std::string q_text = fmt::format("{:.4f}", fmt::join(user_from_actuators(mech, *q), " "));
      if (!fk) {
        ++failures;
        std::cout << fmt::format("{:<58} {}  FK failed: {}\n", pose_text, q_text, fk.error().message);
        continue;
      }
      const PoseDistance d = pose_distance(fk->pose, *pose);
      std::cout << fmt::format("{:<58} {}  {:12.3e} {:12.3e} {:5}{}\n", pose_text, q_text, d.position_mm,
                               deg_from_rad(d.rotation_rad), fk->iterations, range_note);
    }
    std::cout << fmt::format("\n(FK started cold from home for every row; names: {})\n",
                             fmt::join(names, ","));
    exit_code = failures == 0 ? 0 : 4;
  });
}

}  // namespace pkm::cli
