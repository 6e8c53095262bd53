// pkm compliance --machine M.yaml --pose P [--json]: the tool's compliance at a pose when the struts are the
// elastic parts (src/stiffness/strut_compliance.hpp, docs/stiffness.md): the 6 × 6 matrix about the tool
// point, the principal stiffness in N/µm with its directions, and the struts' stiffness used.
#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/pose_input.hpp"
#include "number_options.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::cli {
namespace {

std::vector<double> vector_of(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

// N/mm → N/µm and N·mm/rad → N·m/mrad.
constexpr double kNPerUmPerNPerMm = 1e-3, kNmPerMradPerNmmPerRad = 1e-6;

// A stiffness in JSON; infinite (a direction the mechanism does not allow) as null.
nlohmann::json stiffness_json(double value, double unit) {
  return std::isfinite(value) ? nlohmann::json(value * unit) : nlohmann::json(nullptr);
}

}  // namespace

void add_compliance_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "compliance", "the tool's compliance and principal stiffness at a pose, the struts as the springs");
  auto machine_path = std::make_shared<std::string>();
  auto pose_text = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--machine", *machine_path, "machine file (YAML) with a stiffness: section")->required();
  cmd->add_option("--pose", *pose_text, "pose, as for pkm ik (planar: x,y[,phi])")->required();
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("compliance", machine.error());
      return;
    }
    const Mechanism& mech = *machine->mechanism;
    auto values = parse_number_list(*pose_text, "--pose");
    auto pose = values ? pose_from_user(mech, *values, "--pose") : Result<Pose>(values.error());
    if (!pose) {
      exit_code = report_error("compliance", pose.error());
      return;
    }
    auto actuators = mech.inverse(*pose);
    Status in_range = actuators ? check_actuator_range(*machine, *actuators) : Status(actuators.error());
    auto parameters = stiffness::strut_stiffness_of(*machine);
    auto compliance = !in_range     ? Result<stiffness::ToolCompliance>(in_range.error())
                      : !parameters ? Result<stiffness::ToolCompliance>(parameters.error())
                                    : stiffness::strut_compliance(mech, *parameters, *pose);
    if (!compliance) {
      Error e = compliance.error();
      if (e.location.file.empty()) e.message = fmt::format("--pose {}: {}", *pose_text, e.message);
      exit_code = report_error("compliance", e);
      return;
    }
    const auto translation = stiffness::principal_stiffness(*compliance, false);
    const auto rotation = stiffness::principal_stiffness(*compliance, true);
    const stiffness::Matrix6& c = compliance->compliance;
    if (*json) {
      nlohmann::json matrix = nlohmann::json::array();
      for (int r = 0; r < 6; ++r) {
        std::vector<double> row(6);
        for (int k = 0; k < 6; ++k) row[k] = c(r, k);
        matrix.push_back(row);
      }
      nlohmann::json principal = nlohmann::json::array();
      for (int i = 0; i < 3; ++i) {
        principal.push_back({{"stiffness_N_um", stiffness_json(translation.stiffness[i], kNPerUmPerNPerMm)},
                             {"direction", vector_of(translation.directions.col(i))}});
      }
      nlohmann::json turning = nlohmann::json::array();
      for (int i = 0; i < 3; ++i) {
        turning.push_back(
            {{"stiffness_Nm_mrad", stiffness_json(rotation.stiffness[i], kNmPerMradPerNmmPerRad)},
             {"axis", vector_of(rotation.directions.col(i))}});
      }
      print_json(
          {{"machine", machine->source},
           {"pose", user_from_pose(mech, *pose)},
           {"dof", compliance->dof},
           {"compliance", matrix},
           {"compliance_units", "rows dx dy dz (mm), rx ry rz (rad); columns fx fy fz (N), mx my mz (N·mm)"},
           {"translational", principal},
           {"rotational", turning},
           {"strut_stiffness_N_mm", std::vector<double>(compliance->strut_stiffness_N_mm.data(),
                                                        compliance->strut_stiffness_N_mm.data() +
                                                            compliance->strut_stiffness_N_mm.size())}});
      return;
    }
    std::cout << fmt::format("{} ({}) at {}: the struts as the springs, {} allowed motions\n", machine->name,
                             machine->source, *pose_text, compliance->dof);
    std::cout << "  translational stiffness (N/µm) along its principal directions, the weakest first:\n";
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d d = translation.directions.col(i);
      std::cout << fmt::format("    {:>12.3f}   [{:+.4f} {:+.4f} {:+.4f}]\n",
                               translation.stiffness[i] * kNPerUmPerNPerMm, d.x(), d.y(), d.z());
    }
    std::cout << "  rotational stiffness (N·m/mrad) about its principal axes, the weakest first:\n";
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d d = rotation.directions.col(i);
      std::cout << fmt::format("    {:>12.3f}   [{:+.4f} {:+.4f} {:+.4f}]\n",
                               rotation.stiffness[i] * kNmPerMradPerNmmPerRad, d.x(), d.y(), d.z());
    }
    std::cout
        << "  compliance about the tool point (µm/N; rows dx dy dz, rx ry rz in µrad; columns fx fy fz, "
           "mx my mz per N·m):\n";
    for (int r = 0; r < 6; ++r) {
      std::cout << "   ";
      // mm → µm, rad → µrad; per N·mm → per N·m.
      const double row_scale = r < 3 ? 1e3 : 1e6;
      for (int k = 0; k < 6; ++k)
        std::cout << fmt::format(" {:>12.5g}", c(r, k) * row_scale * (k < 3 ? 1.0 : 1e3));
      std::cout << '\n';
    }
    std::cout << "  struts (N/µm):";
    for (int j = 0; j < compliance->strut_stiffness_N_mm.size(); ++j)
      std::cout << fmt::format(" {:.3f}", compliance->strut_stiffness_N_mm[j] * 1e-3);
    std::cout << '\n';
  });
}

}  // namespace pkm::cli
