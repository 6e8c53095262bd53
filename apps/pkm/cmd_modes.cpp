// pkm modes --machine M.yaml --pose P [--json]: the natural frequencies and mode shapes of the machine's
// elastic struts at a pose (the drives clamped there, about the static equilibrium under gravity;
// src/dynamics/natural_frequencies.hpp, docs/dynamics_elastic.md). With --map instead of --pose, the lowest
// frequency over a plane grid of poses (modes_map.cpp).
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/pose_input.hpp"
#include "modes_map.hpp"
#include "pipeline/modes_job.hpp"

namespace pkm::cli {
namespace {

void print_modes_json(const Machine& machine, const Pose& pose, const pipeline::ModesJobResult& m) {
  nlohmann::json shapes = nlohmann::json::array();
  for (int i = 0; i < m.modes.count; ++i) {
    nlohmann::json shape = nlohmann::json::object();
    for (int k = 0; k < m.modes.count; ++k) shape[m.coordinates[k]] = m.modes.shape(k, i);
    shapes.push_back({{"frequency_Hz", m.modes.frequency_Hz[i]}, {"shape", shape}});
  }
  const auto& tension = m.modes.equilibrium.strut_force_N;
  const Eigen::Vector3d& sag = m.static_deflection_mm;
  print_json({{"machine", machine.source},
              {"pose", user_from_pose(*machine.mechanism, pose)},
              {"frequencies_Hz",
               std::vector<double>(m.modes.frequency_Hz.data(), m.modes.frequency_Hz.data() + m.modes.count)},
              {"modes", shapes},
              {"static_deflection_mm", {sag.x(), sag.y(), sag.z()}},
              {"static_rotation_deg", m.static_rotation_deg},
              {"strut_tension_N", std::vector<double>(tension.data(), tension.data() + tension.size())},
              {"geometric_stiffness_share", m.modes.geometric_share},
              {"units",
               "shapes: twist coordinates of the platform about the tool point, base frame (mm, rad), "
               "scaled to a largest platform-joint motion of 1 mm"}});
}

void print_modes_table(const Machine& machine, const std::string& pose_text,
                       const pipeline::ModesJobResult& m) {
  std::cout << fmt::format("{} ({}) at {}: drives clamped, about the static equilibrium under gravity\n",
                           machine.name, machine.source, pose_text);
  const Eigen::Vector3d& sag = m.static_deflection_mm;
  std::cout << fmt::format(
      "  static deflection of the tool point {:.4f} µm (x {:.4f}, y {:.4f}, z {:.4f} µm), "
      "rotation {:.3g}°\n",
      sag.norm() * 1e3, sag.x() * 1e3, sag.y() * 1e3, sag.z() * 1e3, m.static_rotation_deg);
  std::cout << fmt::format("  mode  frequency Hz  shape (largest platform-joint motion 1 mm): {}\n",
                           fmt::join(m.coordinates, " "));
  for (int i = 0; i < m.modes.count; ++i) {
    std::cout << fmt::format("  {:4d}  {:12.3f} ", i + 1, m.modes.frequency_Hz[i]);
    for (int k = 0; k < m.modes.count; ++k) std::cout << fmt::format(" {:10.6f}", m.modes.shape(k, i));
    std::cout << "\n";
  }
}

int run_modes_at_pose(const std::string& machine_path, const std::string& pose_text, bool json) {
  if (pose_text.empty())
    return report_error(
        "modes", make_error(ErrorCode::bad_input, "give --pose P (one pose), or --map --out FILE (a map)"));
  auto machine = load_machine_or_report(machine_path);
  if (!machine) return report_error("modes", machine.error());
  auto values = parse_number_list(pose_text, "--pose");
  if (!values) return report_error("modes", values.error());
  auto pose = pose_from_user(*machine->mechanism, *values, "--pose");
  if (!pose) return report_error("modes", pose.error());
  auto modes = pipeline::run_modes_job(*machine, {*pose, "--pose " + pose_text});
  if (!modes) return report_error("modes", modes.error());
  if (json)
    print_modes_json(*machine, *pose, *modes);
  else
    print_modes_table(*machine, pose_text, *modes);
  return 0;
}

}  // namespace

void add_modes_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "modes", "natural frequencies and mode shapes of the elastic struts at a pose (dynamics: section)");
  auto machine_path = std::make_shared<std::string>();
  auto pose_text = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto map = std::make_shared<bool>(false);
  auto map_arguments = std::make_shared<ModesMapArguments>();
  cmd->add_option("--machine", *machine_path, "machine file (YAML) with stiffness_N_mm for every strut")
      ->required();
  auto* pose_option = cmd->add_option("--pose", *pose_text, "pose, as for pkm ik (planar: x,y[,phi])");
  auto* map_flag =
      cmd->add_flag("--map", *map,
                    "instead of --pose: the lowest frequency over a plane grid of poses, to --out")
          ->excludes(pose_option);
  auto* out_option =
      cmd->add_option("--out", map_arguments->out_path, "with --map: the map's CSV file")->needs(map_flag);
  map_flag->needs(out_option);
  add_map_grid_options(*cmd, map_arguments->grid, map_flag);
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=, &exit_code] {
    if (*map) {
      map_arguments->machine_path = *machine_path;
      map_arguments->json = *json;
      exit_code = run_modes_map(*map_arguments);
      return;
    }
    exit_code = run_modes_at_pose(*machine_path, *pose_text, *json);
  });
}

}  // namespace pkm::cli
