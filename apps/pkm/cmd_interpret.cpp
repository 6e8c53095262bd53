// pkm interpret PROGRAM [--machine M.yaml] [--tool-table T.tbl] [--json]: the canonical moves of a part
// program (G-code, or APT CL data by extension), in mm and degrees.
#include <fmt/format.h>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/json_text.hpp"
#include "program/move_kind_name.hpp"
#include "program/part_program.hpp"

namespace pkm::cli {

namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json move_json(const program::CanonicalMove& m) {
  nlohmann::json j;
  j["line"] = m.line;
  j["kind"] = program::move_kind_name(m.kind);
  j["end"] = {m.end_mm.x(),      m.end_mm.y(),      m.end_mm.z(),
              m.end_abc_deg.x(), m.end_abc_deg.y(), m.end_abc_deg.z()};
  if (m.kind == program::MoveKind::arc) {
    j["center"] = vector_json(m.center_mm);
    j["normal"] = vector_json(m.normal);
    j["turns"] = m.turns;
  }
  j["feed_mm_min"] = m.feed_mm_min;
  if (m.inverse_time) j["inverse_time_per_min"] = m.inverse_time_per_min;
  if (m.kind == program::MoveKind::dwell) j["dwell_s"] = m.dwell_s;
  return j;
}

// The array as json.dump(2) would print it, one move at a time: a JSON document of every move of a
// 3-million-line program took more than 3 GB; this needs one move's worth.
void print_moves_json(const program::CanonicalProgram& program) {
  if (program.moves.empty()) {
    std::cout << "[]\n";
    return;
  }
  std::cout << "[\n";
  for (std::size_t i = 0; i < program.moves.size(); ++i) {
    std::string element = json_text(move_json(program.moves[i]));
    std::string indented = "  ";
    indented.reserve(element.size() + element.size() / 8);
    for (const char c : element) {
      indented.push_back(c);
      if (c == '\n') indented.append("  ");
    }
    std::cout << indented << (i + 1 < program.moves.size() ? ",\n" : "\n");
  }
  std::cout << "]\n";
}

void print_table(const program::CanonicalProgram& program) {
  std::cout << fmt::format("{:>6}  {:<5}  {:>11} {:>11} {:>11}  {:>9} {:>9} {:>9}  {:>10}  {}\n", "line",
                           "kind", "x mm", "y mm", "z mm", "a deg", "b deg", "c deg", "feed", "detail");
  for (const program::CanonicalMove& m : program.moves) {
    std::string detail;
    if (m.kind == program::MoveKind::arc) {
      detail = fmt::format("centre {:.4f},{:.4f},{:.4f} normal {:g},{:g},{:g}", m.center_mm.x(),
                           m.center_mm.y(), m.center_mm.z(), m.normal.x(), m.normal.y(), m.normal.z());
      if (m.turns > 1) detail.append(fmt::format(" turns {}", m.turns));
    } else if (m.kind == program::MoveKind::dwell) {
      detail = fmt::format("{:g} s", m.dwell_s);
    }
    if (m.inverse_time) detail.append(fmt::format(" (G93 F{:g}/min)", m.inverse_time_per_min));
    std::cout << fmt::format(
        "{:>6}  {:<5}  {:>11.4f} {:>11.4f} {:>11.4f}  {:>9.4f} {:>9.4f} {:>9.4f}  {:>10.1f}  {}\n", m.line,
        program::move_kind_name(m.kind), m.end_mm.x(), m.end_mm.y(), m.end_mm.z(), m.end_abc_deg.x(),
        m.end_abc_deg.y(), m.end_abc_deg.z(), m.feed_mm_min, detail);
  }
  for (const program::ProgramEvent& e : program.events)
    std::cout << fmt::format("{:>6}  {}\n", e.line, e.what);
  std::cout << fmt::format("{} moves, {} events, program ends on line {}\n", program.moves.size(),
                           program.events.size(), program.end_line);
}

}  // namespace

void add_interpret_command(CLI::App& app, int& exit_code) {
  auto* cmd =
      app.add_subcommand("interpret", "the canonical moves of a part program (G-code or APT CL data)");
  auto program_path = std::make_shared<std::string>();
  auto machine_path = std::make_shared<std::string>();
  auto tool_table = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("program", *program_path, "part program: G-code, or APT CL data (.cl, .cls, .apt)")
      ->required();
  cmd->add_option("--machine", *machine_path, "machine file (YAML); only validated for now");
  cmd->add_option("--tool-table", *tool_table, "LinuxCNC tool table for G43 (lengths in mm)");
  cmd->add_flag("--json", *json, "print the moves as a JSON array");
  cmd->callback([=, &exit_code] {
    if (!machine_path->empty()) {
      auto machine = load_machine_or_report(*machine_path);
      if (!machine) {
        exit_code = report_error("interpret", machine.error());
        return;
      }
    }
    program::InterpretOptions options;
    options.tool_table_path = *tool_table;
    auto program = program::load_part_program(*program_path, options);
    if (!program) {
      exit_code = report_error("interpret", program.error());
      return;
    }
    if (*json) {
      print_moves_json(*program);
    } else {
      print_table(*program);
    }
    exit_code = 0;
  });
}

}  // namespace pkm::cli
