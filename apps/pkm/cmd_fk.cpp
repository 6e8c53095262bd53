// pkm fk --machine M.yaml --actuators q1,..,qn [--guess pose] [--all] [--json]: pose(s) from actuator
// positions.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/pose_input.hpp"

namespace pkm::cli {
namespace {

nlohmann::json solution_json(const Mechanism& mech, const FkSolution& s) {
  return {{"pose", user_from_pose(mech, s.pose)},
          {"iterations", s.iterations},
          {"residual_mm", s.residual_mm},
          {"branch", s.branch}};
}

void print_solution(const Mechanism& mech, const FkSolution& s) {
  const auto names = pose_coordinate_names(mech);
  const auto values = user_from_pose(mech, s.pose);
  std::vector<std::string> parts;
  const bool planar = mech.is_planar();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string name = planar && i == 2 ? "phi" : names[i];
    parts.push_back(fmt::format("{}={:.10f}", name, values[i]));
  }
  std::cout << fmt::format("{}  (mm, deg; {} iterations, residual {:.2e} mm, assembly mode {})\n",
                           fmt::join(parts, " "), s.iterations, s.residual_mm, s.branch);
}

}  // namespace

void add_fk_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("fk", "forward kinematics: the pose from actuator positions");
  auto machine_path = std::make_shared<std::string>();
  auto actuators_text = std::make_shared<std::string>();
  auto guess_text = std::make_shared<std::string>();
  auto all = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--machine", *machine_path, "machine file (YAML)")->required();
  cmd->add_option("--actuators", *actuators_text,
                  "actuator positions q1,..,qn (mm, or deg for angular actuators)")
      ->required();
  cmd->add_option("--guess", *guess_text, "start pose (default: the machine's home); same form as ik --pose");
  cmd->add_flag("--all", *all, "all assembly modes (where the mechanism can enumerate them)");
  cmd->add_flag("--json", *json, "print JSON");
  cmd->callback([=, &exit_code] {
    auto machine = load_machine_or_report(*machine_path);
    if (!machine) {
      exit_code = report_error("fk", machine.error());
      return;
    }
    const Mechanism& mech = *machine->mechanism;
    auto values = parse_number_list(*actuators_text, "--actuators");
    if (!values) {
      exit_code = report_error("fk", values.error());
      return;
    }
    auto q = actuators_from_user(mech, *values, "--actuators");
    if (!q) {
      exit_code = report_error("fk", q.error());
      return;
    }
    if (auto range = check_actuator_range(*machine, *q); !range) {
      exit_code = report_error("fk", range.error());
      return;
    }
    if (*all) {
      FkOptions every_core;
      every_core.threads = 0;  // one solve: its paths on every core
      auto modes = mech.assembly_modes(*q, every_core);
      if (!modes) {
        exit_code = report_error("fk", modes.error());
        return;
      }
      const AssemblyModeReport& report = modes->report;
      if (*json) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& s : modes->solutions) list.push_back(solution_json(mech, s));
        nlohmann::json seen = {{"method", report.method}, {"real", report.real}, {"failed", report.failed}};
        // −1: the method does not see them (written as null).
        auto count = [](int n) { return n < 0 ? nlohmann::json(nullptr) : nlohmann::json(n); };
        seen["complex"] = count(report.complex);
        seen["at_infinity"] = count(report.at_infinity);
        seen["singular"] = count(report.singular);
        print_json({{"solutions", list}, {"report", seen}});
      } else {
        std::cout << modes->solutions.size() << " assembly modes (nearest to home first), by "
                  << report.method;
        if (report.complex >= 0) {
          std::cout << "; besides them " << report.complex << " complex, " << report.at_infinity
                    << " at infinity, " << report.singular << " singular";
        }
        if (report.failed > 0) std::cout << "; " << report.failed << " paths could not be followed";
        std::cout << ":\n";
        for (const auto& s : modes->solutions) print_solution(mech, s);
      }
      exit_code = 0;
      return;
    }
    Pose guess = mech.home();
    if (!guess_text->empty()) {
      auto guess_values = parse_number_list(*guess_text, "--guess");
      if (!guess_values) {
        exit_code = report_error("fk", guess_values.error());
        return;
      }
      auto parsed = pose_from_user(mech, *guess_values, "--guess");
      if (!parsed) {
        exit_code = report_error("fk", parsed.error());
        return;
      }
      guess = *parsed;
    }
    auto solution = mech.forward(*q, guess);
    if (!solution) {
      exit_code = report_error("fk", solution.error());
      return;
    }
    if (*json) {
      print_json(solution_json(mech, *solution));
    } else {
      print_solution(mech, *solution);
    }
    exit_code = 0;
  });
}

}  // namespace pkm::cli
