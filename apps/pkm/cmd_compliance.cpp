// pkm compliance --machine M.yaml --pose P [--json]: the tool's compliance at a pose when the struts are the
// elastic parts (src/stiffness/strut_compliance.hpp, docs/stiffness.md): the 6 × 6 matrix about the tool
// point, the principal stiffness in N/µm with its directions, and the struts' stiffness used. With
// --bode FILE also the dynamic compliance's natural frequencies and Bode data (compliance_bode_cli.cpp,
// docs/dynamic_compliance.md); with --map --out FILE instead of --pose the lowest stiffness over a plane grid
// of poses (compliance_map_cli.cpp).
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <optional>

#include "cli_common.hpp"
#include "commands.hpp"
#include "compliance_cli.hpp"
#include "io/pose_input.hpp"
#include "number_options.hpp"
#include "pipeline/compliance_job.hpp"

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

struct ComplianceArguments {
  std::string machine_path;
  std::string pose_text;
  bool json = false;
  ComplianceBodeArguments bode;
  bool map = false;
  ComplianceMapArguments map_arguments;
};

nlohmann::json compliance_json(const Machine& machine, const Pose& pose,
                               const stiffness::ToolCompliance& compliance) {
  const auto translation = stiffness::principal_stiffness(compliance, false);
  const auto rotation = stiffness::principal_stiffness(compliance, true);
  nlohmann::json matrix = nlohmann::json::array();
  for (int r = 0; r < 6; ++r) {
    std::vector<double> row(6);
    for (int k = 0; k < 6; ++k) row[k] = compliance.compliance(r, k);
    matrix.push_back(row);
  }
  nlohmann::json principal = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) {
    principal.push_back({{"stiffness_N_um", stiffness_json(translation.stiffness[i], kNPerUmPerNPerMm)},
                         {"direction", vector_of(translation.directions.col(i))}});
  }
  nlohmann::json turning = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) {
    turning.push_back({{"stiffness_Nm_mrad", stiffness_json(rotation.stiffness[i], kNmPerMradPerNmmPerRad)},
                       {"axis", vector_of(rotation.directions.col(i))}});
  }
  const ActuatorVector& struts = compliance.strut_stiffness_N_mm;
  return {{"machine", machine.source},
          {"pose", user_from_pose(*machine.mechanism, pose)},
          {"dof", compliance.dof},
          {"compliance", matrix},
          {"compliance_units", "rows dx dy dz (mm), rx ry rz (rad); columns fx fy fz (N), mx my mz (N·mm)"},
          {"translational", principal},
          {"rotational", turning},
          {"strut_stiffness_N_mm", std::vector<double>(struts.data(), struts.data() + struts.size())}};
}

void print_compliance(const Machine& machine, const std::string& pose_text,
                      const stiffness::ToolCompliance& compliance) {
  const auto translation = stiffness::principal_stiffness(compliance, false);
  const auto rotation = stiffness::principal_stiffness(compliance, true);
  std::cout << fmt::format("{} ({}) at {}: the struts as the springs, {} allowed motions\n", machine.name,
                           machine.source, pose_text, compliance.dof);
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
  std::cout << "  compliance about the tool point (µm/N; rows dx dy dz, rx ry rz in µrad; columns fx fy fz, "
               "mx my mz per N·m):\n";
  for (int r = 0; r < 6; ++r) {
    std::cout << "   ";
    // mm → µm, rad → µrad; per N·mm → per N·m.
    const double row_scale = r < 3 ? 1e3 : 1e6;
    for (int k = 0; k < 6; ++k)
      std::cout << fmt::format(" {:>12.5g}", compliance.compliance(r, k) * row_scale * (k < 3 ? 1.0 : 1e3));
    std::cout << '\n';
  }
  std::cout << "  struts (N/µm):";
  for (int j = 0; j < compliance.strut_stiffness_N_mm.size(); ++j)
    std::cout << fmt::format(" {:.3f}", compliance.strut_stiffness_N_mm[j] * 1e-3);
  std::cout << '\n';
}

int run_compliance_at_pose(const ComplianceArguments& a) {
  if (a.pose_text.empty())
    return report_error("compliance", make_error(ErrorCode::bad_input,
                                                 "give --pose P (one pose), or --map --out FILE (a map)"));
  auto machine = load_machine_or_report(a.machine_path);
  if (!machine) return report_error("compliance", machine.error());
  auto values = parse_number_list(a.pose_text, "--pose");
  auto pose = values ? pose_from_user(*machine->mechanism, *values, "--pose") : Result<Pose>(values.error());
  if (!pose) return report_error("compliance", pose.error());
  pipeline::ComplianceJob job{*pose, "--pose " + a.pose_text, std::nullopt, a.bode.path, "--bode"};
  if (!a.bode.path.empty()) {
    auto request = compliance_bode_request(a.bode);
    if (!request) return report_error("compliance", request.error());
    job.bode = *request;
  }
  auto result = pipeline::run_compliance_job(*machine, job);
  if (!result) return report_error("compliance", result.error());
  if (a.json) {
    nlohmann::json out = compliance_json(*machine, *pose, result->compliance);
    if (result->bode) out["dynamic"] = compliance_bode_json(*result->bode, a.bode);
    print_json(out);
    return 0;
  }
  print_compliance(*machine, a.pose_text, result->compliance);
  if (result->bode) print_compliance_bode(*result->bode, a.bode);
  return 0;
}

}  // namespace

void add_compliance_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "compliance",
      "the tool's compliance and principal stiffness at a pose, the struts as the springs; its dynamic "
      "compliance (--bode); the lowest stiffness over a plane of poses (--map)");
  auto a = std::make_shared<ComplianceArguments>();
  ComplianceBodeArguments* bode = &a->bode;
  cmd->add_option("--machine", a->machine_path, "machine file (YAML) with a stiffness: section")->required();
  auto* pose_option = cmd->add_option("--pose", a->pose_text, "pose, as for pkm ik (planar: x,y[,phi])");
  cmd->add_flag("--json", a->json, "print JSON");
  auto* bode_option = cmd->add_option(
      "--bode", bode->path,
      "with --pose: write the dynamic compliance's Bode data to this CSV (needs a dynamics: section)");
  bode_option->needs(pose_option);
  // Beyond 1 MHz no structural mode of a machine tool lives, and a log sweep needs positive ends.
  cmd->add_option("--f-min-hz", bode->f_min_Hz, "with --bode: the lowest frequency, Hz")
      ->capture_default_str()
      ->check(number_in({0.0, 1e6, false, true, "Hz"}))
      ->needs(bode_option);
  cmd->add_option("--f-max-hz", bode->f_max_Hz, "with --bode: the highest frequency, Hz")
      ->capture_default_str()
      ->check(number_in({0.0, 1e6, false, true, "Hz"}))
      ->needs(bode_option);
  cmd->add_option("--points", bode->points, "with --bode: frequencies, log-spaced, both ends included")
      ->capture_default_str()
      ->check(number_in({2.0, 100000.0, true, true, "", true}))
      ->needs(bode_option);
  auto* ratio_option = cmd->add_option("--damping-ratio", bode->damping_ratio,
                                       "with --bode: the modal damping ratio ζ assumed for every mode")
                           ->capture_default_str()
                           ->check(number_in({0.0, 10.0, true, true, ""}))
                           ->needs(bode_option);
  cmd->add_option("--rayleigh", bode->rayleigh_text,
                  "with --bode, instead of --damping-ratio: Rayleigh damping C = α·M + β·K, as α,β (1/s, s)")
      ->needs(bode_option)
      ->excludes(ratio_option);
  auto* map_flag =
      cmd->add_flag("--map", a->map,
                    "instead of --pose: the lowest translational stiffness over a plane grid of poses, to "
                    "--out")
          ->excludes(pose_option);
  auto* out_option =
      cmd->add_option("--out", a->map_arguments.out_path, "with --map: the map's CSV file")->needs(map_flag);
  map_flag->needs(out_option);
  add_map_grid_options(*cmd, a->map_arguments.grid, map_flag);
  cmd->callback([a, &exit_code] {
    if (a->map) {
      a->map_arguments.machine_path = a->machine_path;
      a->map_arguments.json = a->json;
      exit_code = run_compliance_map(a->map_arguments);
      return;
    }
    exit_code = run_compliance_at_pose(*a);
  });
}

}  // namespace pkm::cli
