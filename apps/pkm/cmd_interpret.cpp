// pkm interpret PROGRAM [--machine M.yaml] [--tool-table T.tbl] [--subroutine-path DIR]... [--parameter-file
// F.var [--write-parameter-file]] [--format F] [--no-transform] [--json | --count]: the canonical moves of a
// part program (G-code, or CL data: the language and CAM dialect from the content), in mm and degrees: work
// coordinates, and with --json also the program's own; CL data's tool axes where G-code has A B C.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "io/json_text.hpp"
#include "program/move_kind_name.hpp"
#include "program/part_program.hpp"
#include "program_options.hpp"

namespace pkm::cli {

namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json pose_json(const Eigen::Vector3d& mm, const Eigen::Vector3d& deg) {
  return nlohmann::json::array({mm.x(), mm.y(), mm.z(), deg.x(), deg.y(), deg.z()});
}

const char* plane_name(program::Plane plane) {
  switch (plane) {
    case program::Plane::xy:
      return "xy";
    case program::Plane::zx:
      return "zx";
    case program::Plane::yz:
      return "yz";
  }
  return "?";
}

nlohmann::json frame_json(const program::CanonicalProgram& program, int index) {
  const std::size_t i = static_cast<std::size_t>(index);
  const program::WorkFrame frame = i < program.frames.size() ? program.frames[i] : program::WorkFrame{};
  return {{"index", index},
          {"system", frame.system},
          {"g5x", pose_json(frame.g5x_mm, frame.g5x_abc_deg)},
          {"xy_rotation_deg", frame.xy_rotation_deg},
          {"g92", pose_json(frame.g92_mm, frame.g92_abc_deg)}};
}

// One move: "end"/"center" in work coordinates (what the machine does), "program_end"/"program_center" as
// the program wrote them (what LinuxCNC's canonical calls print); print_program_json adds the frame between.
nlohmann::json move_json(const program::CanonicalProgram& program, const program::CanonicalMove& m) {
  const program::ProgramCoordinates own = program::program_coordinates(program, m);
  nlohmann::json j;
  j["line"] = m.line;
  j["kind"] = program::move_kind_name(m.kind);
  j["file"] = m.source_file;
  j["source_line"] = m.source_line;
  j["end"] = pose_json(m.end_mm, m.end_abc_deg);
  j["program_end"] = pose_json(own.end_mm, own.end_abc_deg);
  if (m.kind == program::MoveKind::arc) {
    j["center"] = vector_json(m.center_mm);
    j["program_center"] = vector_json(own.center_mm);
    j["normal"] = vector_json(m.normal);
    j["turns"] = m.turns;
  }
  j["plane"] = plane_name(m.plane);
  j["feed_mm_min"] = m.feed_mm_min;
  if (m.inverse_time) j["inverse_time_per_min"] = m.inverse_time_per_min;
  if (m.feed_per_revolution_mm > 0.0) j["feed_per_revolution_mm"] = m.feed_per_revolution_mm;
  if (m.probe) j["probe"] = true;
  if (m.inserted) j["inserted"] = true;
  if (m.kind == program::MoveKind::dwell) j["dwell_s"] = m.dwell_s;
  if (m.orientation == program::OrientationSource::tool_axis) j["tool_axis"] = vector_json(m.tool_axis);
  j["tool_length_mm"] = m.tool_length_mm;
  if (m.path_tolerance_mm >= 0.0) j["path_tolerance_mm"] = m.path_tolerance_mm;
  if (m.exact_stop) j["exact_stop"] = true;
  return j;
}

// `text` with `indent` after every line break: a JSON value nested one level deeper, as json.dump(2) does.
std::string nested(const std::string& text, const std::string& indent) {
  std::string out;
  out.reserve(text.size() + text.size() / 4);
  for (const char c : text) {
    out.push_back(c);
    if (c == '\n') out.append(indent);
  }
  return out;
}

void print_nested(const std::string& text, const std::string& indent) {
  std::cout << indent << nested(text, indent);
}

// The document as json.dump(2) would print it, one move at a time: a JSON document of every move of a
// 3-million-line program took more than 3 GB; this needs one move's worth (and one frame's per frame).
void print_program_json(const program::CanonicalProgram& program) {
  std::cout << "{\n  \"source\": " << json_text(nlohmann::json(program.source))
            << ",\n  \"format\": " << json_text(nlohmann::json(program.format)) << ",\n  \"files\": ";
  // files[0] is the program itself; a reader that lists no files (CL data) read only that one.
  std::string files = json_text(
      nlohmann::json(program.files.empty() ? std::vector<std::string>{program.source} : program.files));
  for (std::size_t at = files.find('\n'); at != std::string::npos; at = files.find('\n', at + 3))
    files.replace(at, 1, "\n  ");
  std::cout << files << ",\n  \"moves\": [";
  // Each frame's text is made once and closes its moves' objects: a million moves share a few frames.
  std::vector<std::string> frames(program.frames.size() + 1);
  for (std::size_t i = 0; i < program.moves.size(); ++i) {
    const program::CanonicalMove& m = program.moves[i];
    const std::size_t f = std::min(static_cast<std::size_t>(std::max(m.frame, 0)), program.frames.size());
    if (frames[f].empty())
      frames[f] = ",\n  \"frame\": " + nested(json_text(frame_json(program, m.frame)), "  ") + "\n}";
    std::string text = json_text(move_json(program, m));
    text.replace(text.size() - 2, 2, frames[f]);  // "\n}" closes the dump
    std::cout << (i == 0 ? "\n" : ",\n");
    print_nested(text, "    ");
  }
  std::cout << (program.moves.empty() ? "],\n" : "\n  ],\n") << "  \"events\": [";
  for (std::size_t i = 0; i < program.events.size(); ++i) {
    const program::ProgramEvent& e = program.events[i];
    const nlohmann::json event = {
        {"line", e.line}, {"file", e.source_file}, {"source_line", e.source_line}, {"what", e.what}};
    std::cout << (i == 0 ? "\n" : ",\n");
    print_nested(json_text(event), "    ");
  }
  std::cout << (program.events.empty() ? "],\n" : "\n  ],\n")
            << "  \"notes\": " << json_text(nlohmann::json(program.notes))
            << ",\n  \"end_line\": " << program.end_line << "\n}\n";
}

// "sub.ngc:12" for a move or event written in another file than the main program; "" otherwise.
std::string written_in(const program::CanonicalProgram& program, int file, int line) {
  if (file <= 0 || static_cast<std::size_t>(file) >= program.files.size()) return "";
  return fmt::format("{}:{}",
                     std::filesystem::path(program.files[static_cast<std::size_t>(file)]).filename().string(),
                     line);
}

std::string move_detail(const program::CanonicalProgram& program, const program::CanonicalMove& m) {
  std::string detail;
  if (m.kind == program::MoveKind::arc) {
    detail = fmt::format("centre {:.4f},{:.4f},{:.4f} normal {:g},{:g},{:g}", m.center_mm.x(),
                         m.center_mm.y(), m.center_mm.z(), m.normal.x(), m.normal.y(), m.normal.z());
    if (m.turns > 1) detail.append(fmt::format(" turns {}", m.turns));
  } else if (m.kind == program::MoveKind::dwell) {
    detail = fmt::format("{:g} s", m.dwell_s);
  }
  if (m.inverse_time) detail.append(fmt::format(" (G93 F{:g}/min)", m.inverse_time_per_min));
  const std::string where = written_in(program, m.source_file, m.source_line);
  if (!where.empty()) detail.append((detail.empty() ? "" : " ") + where);
  return detail;
}

void print_summary(const program::CanonicalProgram& program) {
  std::cout << fmt::format("{} moves, {} events, program ends on line {}{}\n", program.moves.size(),
                           program.events.size(), program.end_line,
                           program.format.empty() ? "" : " (" + program.format + ")");
}

// A program that states tool axes (CL data) shows them (i, j, k) where a G-code program shows A B C.
bool states_tool_axes(const program::CanonicalProgram& program) {
  return std::any_of(program.moves.begin(), program.moves.end(), [](const program::CanonicalMove& m) {
    return m.orientation == program::OrientationSource::tool_axis;
  });
}

void print_table(const program::CanonicalProgram& program) {
  const bool axes = states_tool_axes(program);
  std::cout << fmt::format("{:>6}  {:<5}  {:>11} {:>11} {:>11}  {:>9} {:>9} {:>9}  {:>10}  {}\n", "line",
                           "kind", "x mm", "y mm", "z mm", axes ? "tool i" : "a deg",
                           axes ? "tool j" : "b deg", axes ? "tool k" : "c deg", "feed", "detail");
  for (const program::CanonicalMove& m : program.moves) {
    const Eigen::Vector3d& angles =
        m.orientation == program::OrientationSource::tool_axis ? m.tool_axis : m.end_abc_deg;
    std::cout << fmt::format(
        "{:>6}  {:<5}  {:>11.4f} {:>11.4f} {:>11.4f}  {:>9.4f} {:>9.4f} {:>9.4f}  {:>10.1f}  {}\n", m.line,
        program::move_kind_name(m.kind), m.end_mm.x(), m.end_mm.y(), m.end_mm.z(), angles.x(), angles.y(),
        angles.z(), m.feed_mm_min, move_detail(program, m));
  }
  for (const program::ProgramEvent& e : program.events) {
    const std::string where = written_in(program, e.source_file, e.source_line);
    std::cout << fmt::format("{:>6}  {}{}\n", e.line, e.what, where.empty() ? "" : " (" + where + ")");
  }
  print_summary(program);
}

}  // namespace

void add_interpret_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "interpret",
      "the canonical moves of a part program (G-code, or CL data: NX, Creo, CATIA, SolidWorks CAM, APT)");
  auto program_path = std::make_shared<std::string>();
  auto machine_path = std::make_shared<std::string>();
  auto arguments = std::make_shared<ProgramArguments>();
  auto json = std::make_shared<bool>(false);
  auto count = std::make_shared<bool>(false);
  cmd->add_option(
         "program", *program_path,
         "part program: G-code, or CL data (NX, Creo, CATIA, SolidWorks CAM, APT), told apart by content")
      ->required();
  cmd->add_option("--machine", *machine_path, "machine file (YAML); only validated for now");
  add_program_options(*cmd, *arguments);
  auto* json_flag =
      cmd->add_flag("--json", *json,
                    "print the program as JSON: its files, moves (work and program coordinates) and events");
  // Timing the interpreter (scripts/interpret-speed-compare.sh) must not time the printing of a million
  // moves.
  cmd->add_flag("--count", *count, "print only the numbers of moves and events")->excludes(json_flag);
  cmd->callback([=, &exit_code] {
    if (!machine_path->empty()) {
      auto machine = load_machine_or_report(*machine_path);
      if (!machine) {
        exit_code = report_error("interpret", machine.error());
        return;
      }
    }
    auto program =
        program::load_part_program(*program_path, pipeline::interpret_options(arguments->options()));
    if (!program) {
      exit_code = report_error("interpret", program.error());
      return;
    }
    // As LinuxCNC: (PRINT,…) goes to stderr; and what the interpreter noted (no tool table …).
    for (const program::ProgramEvent& e : program->events)
      if (e.what.rfind("PRINT: ", 0) == 0) std::cerr << e.what.substr(7) << "\n";
    for (const std::string& note : program->notes) std::cerr << "pkm interpret: note: " << note << "\n";
    if (*json) {
      print_program_json(*program);
    } else if (*count) {
      print_summary(*program);
    } else {
      print_table(*program);
    }
    exit_code = 0;
  });
}

}  // namespace pkm::cli
