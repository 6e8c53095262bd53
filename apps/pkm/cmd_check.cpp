// pkm check M.yaml [--json]: validates a machine file, prints its structure and mobility, and samples a
// default workspace box around home (±50 mm, ±10°) for the actuator range, singularities and error
// amplification δρ.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/units.hpp"
#include "io/pose_input.hpp"
#include "io/printable_text.hpp"
#include "machine/conditioning.hpp"
#include "machine/mobility.hpp"
#include "number_options.hpp"

namespace pkm::cli {

void add_check_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("check", "validate a machine file; mobility and actuator range around home");
  auto machine_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto half_range_mm = std::make_shared<double>(50.0);
  auto half_angle_deg = std::make_shared<double>(10.0);
  cmd->add_option("machine", *machine_path, "machine file (YAML)")->required();
  // Beyond these the sample says nothing about the machine: no machine pkm models moves metres or turns
  // its platform over.
  cmd->add_option("--range-mm", *half_range_mm, "half-range of the translation sample around home, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 10000.0, true, true, "mm"}));
  cmd->add_option("--range-deg", *half_angle_deg, "half-range of the angle sample around home, deg")
      ->capture_default_str()
      ->check(number_in({0.0, 180.0, true, true, "deg"}));
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("check", machine.error());
      return;
    }
    const Mechanism& mech = *machine->mechanism;
    const MechanismStructure structure = structure_of(mech);
    const int h = mobility(structure);
    WorkspaceBox box;
    box.centre = mech.home();
    box.translation_half_range_mm = *half_range_mm;
    box.angle_half_range_rad = rad_from_deg(*half_angle_deg);
    box.samples_per_axis = mech.controlled_axes().count() > 4 ? 3 : 5;
    const WorkspaceSummary s = sample_workspace(*machine, box);
    const auto unit = actuator_unit_name(mech);
    const auto lo = user_from_actuators(mech, s.actuator_min);
    const auto hi = user_from_actuators(mech, s.actuator_max);
    const auto controlled = controlled_coordinate_names(mech);
    if (*json) {
      print_json({{"valid", true},
                  {"machine", printable_text(machine->name)},
                  {"type", std::string(to_string(mech.type()))},
                  {"structure", structure.notation},
                  {"mobility", h - structure.idle_freedoms},
                  {"mobility_formula",
                   {{"links", structure.links},
                    {"pairs_by_dof", structure.pairs},
                    {"idle", structure.idle_freedoms},
                    {"planar", structure.planar}}},
                  {"controlled", controlled},
                  {"home", user_from_pose(mech, mech.home())},
                  {"sample",
                   {{"poses", s.poses},
                    {"unreachable", s.unreachable},
                    {"out_of_range", s.out_of_range},
                    {"singular", s.singular},
                    {"actuator_min", lo},
                    {"actuator_max", hi},
                    {"unit", unit},
                    {"error_amplification_min", s.error_amplification_min},
                    {"error_amplification_max", s.error_amplification_max},
                    {"condition_max", s.condition_max},
                    {"determinant_changes_sign", s.determinant_changes_sign}}}});
    } else {
      // The name and the path as the user gave them, but never raw bytes a terminal would act on.
      std::cout << fmt::format("{}: valid ({})\n", printable_text(*machine_path),
                               printable_text(machine->name));
      std::cout << fmt::format("  mechanism  {} ({}), {} actuators, controls {}\n", to_string(mech.type()),
                               structure.notation, mech.actuator_count(), fmt::join(controlled, ","));
      std::cout << fmt::format(
          "  mobility   H = {}{} (Somov–Malyshev, {} links, pairs by DOF {})\n", h - structure.idle_freedoms,
          structure.idle_freedoms ? fmt::format(" ({} − {} idle)", h, structure.idle_freedoms) : "",
          structure.links, fmt::join(structure.pairs, "/"));
      std::cout << fmt::format("  home       {}\n", fmt::join(user_from_pose(mech, mech.home()), ", "));
      std::cout << fmt::format(
          "  sample     {} poses around home (±{} mm, ±{} deg): {} unreachable, {} out of range, "
          "{} singular{}\n",
          s.poses, *half_range_mm, *half_angle_deg, s.unreachable, s.out_of_range, s.singular,
          s.determinant_changes_sign ? ", det J changes sign (a singularity inside)" : "");
      for (int j = 0; j < mech.actuator_count(); ++j) {
        std::cout << fmt::format("  actuator {}  {:.3f} … {:.3f} {}\n", j + 1, lo[j], hi[j], unit);
      }
      std::cout << fmt::format(
          "  error amplification δρ {:.3f} … {:.3f} (mm per mm of equal actuator error), "
          "max condition number {:.1f}\n",
          s.error_amplification_min, s.error_amplification_max, s.condition_max);
    }
    exit_code = 0;
  });
}

}  // namespace pkm::cli
