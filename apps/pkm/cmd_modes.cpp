// pkm modes --machine M.yaml --pose P [--json]: the natural frequencies and mode shapes of the machine's
// elastic struts at a pose (the drives clamped there, about the static equilibrium under gravity;
// src/dynamics/natural_frequencies.hpp, docs/dynamics_elastic.md). With --map instead of --pose, the lowest
// frequency over a plane grid of poses (modes_map.cpp).
#include <fmt/format.h>

#include <array>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "core/rotation.hpp"
#include "core/units.hpp"
#include "dynamics/natural_frequencies.hpp"
#include "io/pose_input.hpp"
#include "modes_map.hpp"
#include "number_options.hpp"

namespace pkm::cli {
namespace {

/// The name of each basis coordinate: the twist component it moves (tool point mm, rotation rad).
std::vector<std::string> mode_coordinate_names(const TwistBasis& basis) {
  static const std::array<const char*, 6> kNames = {"x_mm", "y_mm", "z_mm", "rx_rad", "ry_rad", "rz_rad"};
  std::vector<std::string> names;
  for (int k = 0; k < basis.cols(); ++k) {
    int row = 0;
    basis.col(k).cwiseAbs().maxCoeff(&row);
    names.emplace_back(kNames[row]);
  }
  return names;
}

// What the modes at one pose print: the shapes in the basis' coordinates, the static sag and tilt.
struct ModesAtPose {
  dynamics::NaturalModes modes;
  std::vector<std::string> names;
  Eigen::Vector3d sag_mm;
  double tilt_deg = 0.0;
};

void print_modes_json(const Machine& machine, const Pose& pose, const ModesAtPose& m) {
  nlohmann::json shapes = nlohmann::json::array();
  for (int i = 0; i < m.modes.count; ++i) {
    nlohmann::json shape = nlohmann::json::object();
    for (int k = 0; k < m.modes.count; ++k) shape[m.names[k]] = m.modes.shape(k, i);
    shapes.push_back({{"frequency_Hz", m.modes.frequency_Hz[i]}, {"shape", shape}});
  }
  const auto& tension = m.modes.equilibrium.strut_force_N;
  print_json({{"machine", machine.source},
              {"pose", user_from_pose(*machine.mechanism, pose)},
              {"frequencies_Hz",
               std::vector<double>(m.modes.frequency_Hz.data(), m.modes.frequency_Hz.data() + m.modes.count)},
              {"modes", shapes},
              {"static_deflection_mm", {m.sag_mm.x(), m.sag_mm.y(), m.sag_mm.z()}},
              {"static_rotation_deg", m.tilt_deg},
              {"strut_tension_N", std::vector<double>(tension.data(), tension.data() + tension.size())},
              {"geometric_stiffness_share", m.modes.geometric_share},
              {"units",
               "shapes: twist coordinates of the platform about the tool point, base frame (mm, rad), "
               "scaled to a largest platform-joint motion of 1 mm"}});
}

void print_modes_table(const Machine& machine, const std::string& pose_text, const ModesAtPose& m) {
  std::cout << fmt::format("{} ({}) at {}: drives clamped, about the static equilibrium under gravity\n",
                           machine.name, machine.source, pose_text);
  std::cout << fmt::format(
      "  static deflection of the tool point {:.4f} µm (x {:.4f}, y {:.4f}, z {:.4f} µm), "
      "rotation {:.3g}°\n",
      m.sag_mm.norm() * 1e3, m.sag_mm.x() * 1e3, m.sag_mm.y() * 1e3, m.sag_mm.z() * 1e3, m.tilt_deg);
  std::cout << fmt::format("  mode  frequency Hz  shape (largest platform-joint motion 1 mm): {}\n",
                           fmt::join(m.names, " "));
  for (int i = 0; i < m.modes.count; ++i) {
    std::cout << fmt::format("  {:4d}  {:12.3f} ", i + 1, m.modes.frequency_Hz[i]);
    for (int k = 0; k < m.modes.count; ++k) std::cout << fmt::format(" {:10.6f}", m.modes.shape(k, i));
    std::cout << "\n";
  }
}

// The modes at the pose the user gave, refused where the drives cannot hold it.
Result<ModesAtPose> modes_at(const Machine& machine, const Pose& pose, const std::string& pose_text) {
  // The drives must be able to hold the pose: their range, as every other command checks it.
  auto actuators = machine.mechanism->inverse(pose);
  Status in_range = actuators ? check_actuator_range(machine, *actuators) : Status(actuators.error());
  if (!in_range) {
    Error e = in_range.error();
    e.message = fmt::format("--pose {}: {}", pose_text, e.message);
    return e;
  }
  auto model = dynamics::make_elastic_model(machine);
  if (!model) return model.error();
  auto modes = dynamics::natural_modes(*model, pose);
  if (!modes) {
    Error e = modes.error();
    e.message = fmt::format("--pose {}: {}", pose_text, e.message);
    return e;
  }
  ModesAtPose out{std::move(*modes), mode_coordinate_names(model->basis), Eigen::Vector3d::Zero(), 0.0};
  out.sag_mm = out.modes.equilibrium.pose.position_mm - pose.position_mm;
  out.tilt_deg = deg_from_rad(
      rotation_vector_from_rotation(out.modes.equilibrium.pose.rotation * pose.rotation.transpose()).norm());
  return out;
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
  auto modes = modes_at(*machine, *pose, pose_text);
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
  // Kept as text: modes_map.cpp reads it against the mechanism, as --pose is read.
  cmd->add_option("--centre,--center", map_arguments->centre_text,
                  "with --map: the grid's centre pose, as --pose (default: the machine's home)")
      ->needs(map_flag);
  // Like pkm check's sample: beyond 10 m no machine pkm models moves.
  cmd->add_option("--range-mm", map_arguments->half_range_mm,
                  "with --map: the grid covers the centre ± this along both axes, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 10000.0, true, true, "mm"}))
      ->needs(map_flag);
  cmd->add_option("--step-mm", map_arguments->step_mm, "with --map: the grid's step, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 10000.0, false, true, "mm"}))
      ->needs(map_flag);
  cmd->add_option("--plane", map_arguments->plane,
                  "with --map: the grid's plane through the centre, xy|xz|yz")
      ->capture_default_str()
      ->check(CLI::IsMember({"xy", "xz", "yz"}))
      ->needs(map_flag);
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
