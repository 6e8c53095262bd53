// pkm jacobian --machine M.yaml --pose P [--json]: the Jacobian at a pose (actuator rates from
// pose-coordinate rates), its inverse, determinant, condition number and error amplification δρ (dissertation
// eq. 144–146).
#include <fmt/format.h>

#include <Eigen/LU>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/pose_input.hpp"
#include "machine/conditioning.hpp"
#include "pose_reach.hpp"

namespace pkm::cli {
namespace {

nlohmann::json rows_of(const JacobianMatrix& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < m.rows(); ++i) {
    std::vector<double> row;
    for (int k = 0; k < m.cols(); ++k) row.push_back(m(i, k));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

void add_jacobian_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("jacobian", "Jacobian, its inverse, det, condition number and δρ at a pose");
  auto machine_path = std::make_shared<std::string>();
  auto pose_text = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  cmd->add_option("--pose", *pose_text, "pose, as for pkm ik")->required();
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("jacobian", machine.error());
      return;
    }
    const Mechanism& mech = *machine->mechanism;
    auto values = parse_number_list(*pose_text, "--pose");
    if (!values) {
      exit_code = report_error("jacobian", values.error());
      return;
    }
    auto pose = pose_from_user(mech, *values, "--pose");
    if (!pose) {
      exit_code = report_error("jacobian", pose.error());
      return;
    }
    auto j = mech.jacobian(*pose);
    if (!j) {
      exit_code = report_error("jacobian", j.error());
      return;
    }
    auto measures = jacobian_measures(mech, *pose);
    if (!measures) {
      exit_code = report_error("jacobian", measures.error());
      return;
    }
    // A pose pkm ik refuses is refused here alike: its Jacobian would describe a machine that cannot be
    // there.
    if (Status reachable = pose_within_actuator_range(*machine, *pose); !reachable) {
      exit_code = report_error("jacobian", reachable.error());
      return;
    }
    const JacobianMatrix inverse = Eigen::FullPivLU<JacobianMatrix>(*j).inverse();
    const auto columns = controlled_coordinate_names(mech);
    if (*json) {
      print_json({{"columns", columns},
                  {"jacobian", rows_of(*j)},
                  {"inverse", rows_of(inverse)},
                  {"determinant", measures->determinant},
                  {"condition_number", measures->condition_number},
                  {"error_amplification", measures->error_amplification},
                  {"units", "actuator mm (or rad) per mm, or per rad of the angles"}});
    } else {
      std::cout << fmt::format("J = d(actuators)/d({}), angles in rad:\n", fmt::join(columns, ","));
      for (int i = 0; i < j->rows(); ++i) std::cout << fmt::format("  {:12.6f}\n", fmt::join(j->row(i), " "));
      std::cout << "J⁻¹:\n";
      for (int i = 0; i < inverse.rows(); ++i) {
        std::cout << fmt::format("  {:12.6f}\n", fmt::join(inverse.row(i), " "));
      }
      std::cout << fmt::format("det J {:.6g}, condition number {:.3f}, error amplification δρ {:.4f}\n",
                               measures->determinant, measures->condition_number,
                               measures->error_amplification);
    }
    exit_code = 0;
  });
}

}  // namespace pkm::cli
