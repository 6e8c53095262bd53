#include "pipeline/spif_placement_job.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "io/atomic_file.hpp"
#include "io/json_text.hpp"
#include "io/output_set.hpp"

namespace pkm::pipeline {
namespace {

using redundancy::Placement;
using Series = std::vector<std::pair<double, double>>;  // (x, y) points of one curve

nlohmann::json summary_json(const Machine& machine, const SpifPlacementJob& job,
                            const std::vector<Placement>& placements) {
  nlohmann::json json;
  json["program"] = job.program_path;
  json["machine"] = machine.source;
  json["load"] = job.load_text;
  json["step_mm"] = job.placement.step_mm;
  json["energy_accounting"] = redundancy::to_string(job.placement.accounting);
  if (job.placement.law) {
    json["law"] = redundancy::to_string(*job.placement.law);
    nlohmann::json bounds = nlohmann::json::array();
    for (const auto& range : job.placement.law_bounds_deg) bounds.push_back({range[0], range[1]});
    json["law_bounds_deg"] = bounds;
  }
  nlohmann::json rows = nlohmann::json::array();
  const Placement* lowest = nullptr;
  const Placement* highest = nullptr;
  for (const Placement& p : placements) {
    nlohmann::json row{{"z1_mm", p.z1_mm}, {"offset_mm", p.offset_mm}, {"feasible", p.feasible}};
    if (!p.feasible) {
      row["first_infeasible_line"] = p.first_infeasible_line;
    } else {
      row["energy_J"] = p.energy_J;
      row["required_work_J"] = p.required_work_J;
      row["peak_force_N"] = p.peak_force_N;
      if (job.placement.law) row["law_energy_J"] = p.law_energy_J;
      if (!lowest || p.energy_J < lowest->energy_J) lowest = &p;
      if (!highest || p.energy_J > highest->energy_J) highest = &p;
    }
    rows.push_back(row);
  }
  json["placements"] = rows;
  json["lowest_energy"] = {{"z1_mm", lowest->z1_mm}, {"energy_J", lowest->energy_J}};
  json["highest_energy"] = {{"z1_mm", highest->z1_mm}, {"energy_J", highest->energy_J}};
  json["energy_ratio"] = highest->energy_J / lowest->energy_J;
  return json;
}

std::string placement_csv(const std::vector<Placement>& placements) {
  std::string csv = "z1_mm,plane,plane_z_mm,first_line,energy_J,law_energy_J\n";
  for (const Placement& p : placements) {
    if (!p.feasible) continue;
    for (std::size_t i = 0; i < p.planes.size(); ++i) {
      const redundancy::PlaneEnergy& plane = p.planes[i];
      // The law's column is empty where no law was asked.
      csv += fmt::format(
          "{:.6g},{},{:.6f},{},{:.9g},{}\n", p.z1_mm, i + 1, plane.z_mm, plane.first_line, plane.energy_J,
          std::isnan(plane.law_energy_J) ? std::string() : fmt::format("{:.9g}", plane.law_energy_J));
    }
  }
  return csv;
}

// A polyline of (x, y) values in a panel, scaled to the values' ranges; returns the SVG of the panel.
std::string panel(const std::string& title, const std::vector<std::vector<std::pair<double, double>>>& series,
                  double top, const char* const* colours) {
  constexpr double kPanelWidth = 760.0, kPanelHeight = 260.0, kPanelLeft = 60.0;
  double x0 = 1e300, x1 = -1e300, y1 = 0.0;
  for (const auto& s : series)
    for (const auto& [x, y] : s) x0 = std::min(x0, x), x1 = std::max(x1, x), y1 = std::max(y1, y);
  const double dx = std::max(x1 - x0, 1e-9), dy = std::max(y1, 1e-9);
  std::string svg = fmt::format(
      "<rect x=\"{0}\" y=\"{1}\" width=\"{2}\" height=\"{3}\" fill=\"none\" stroke=\"#ccc\"/>\n"
      "<text x=\"{0}\" y=\"{4}\">{5} (0 … {6:.4g} J)</text>\n",
      kPanelLeft, top, kPanelWidth, kPanelHeight, top - 8, title, y1);
  for (std::size_t i = 0; i < series.size(); ++i) {
    if (series[i].empty()) continue;
    std::string d;
    for (const auto& [x, y] : series[i]) {
      d += fmt::format("{}{:.1f},{:.1f}", d.empty() ? "M" : " L", kPanelLeft + kPanelWidth * (x - x0) / dx,
                       top + kPanelHeight * (1.0 - y / dy));
    }
    svg += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n", d, colours[i]);
  }
  return svg;
}

// The drive energy against the first plane's height, and per line (plane) at the lowest and highest heights.
std::string placement_svg(const std::vector<Placement>& placements) {
  static const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c"};
  std::vector<std::pair<double, double>> total;
  std::vector<std::pair<double, double>> total_law;
  const Placement* low = nullptr;
  const Placement* high = nullptr;
  for (const Placement& p : placements) {
    if (!p.feasible) continue;
    total.emplace_back(p.z1_mm, p.energy_J);
    if (!std::isnan(p.law_energy_J)) total_law.emplace_back(p.z1_mm, p.law_energy_J);
    if (!low || p.z1_mm < low->z1_mm) low = &p;
    if (!high || p.z1_mm > high->z1_mm) high = &p;
  }
  auto per_plane = [](const Placement& p, bool law) {
    std::vector<std::pair<double, double>> s;
    for (std::size_t i = 0; i < p.planes.size(); ++i)
      s.emplace_back(static_cast<double>(i + 1), law ? p.planes[i].law_energy_J : p.planes[i].energy_J);
    return s;
  };
  const bool law = !total_law.empty();
  std::string svg =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"880\" height=\"700\" font-family=\"sans-serif\" "
      "font-size=\"13\">\n";
  svg += panel(fmt::format("drive energy against the first plane's height, Z{:g} … Z{:g} mm{}", low->z1_mm,
                           high->z1_mm, law ? ": blue angles held, green chosen by the law" : ""),
               law ? std::vector<Series>{total, {}, total_law} : std::vector<Series>{total}, 40.0, kColours);
  svg +=
      panel(fmt::format("energy per plane, n = 1 … {}: blue first plane at Z{:g}, red at Z{:g}{}",
                        low->planes.size(), low->z1_mm, high->z1_mm,
                        law ? fmt::format(", green Z{:g} by the law", low->z1_mm) : ""),
            law ? std::vector<Series>{per_plane(*low, false), per_plane(*high, false), per_plane(*low, true)}
                : std::vector<Series>{per_plane(*low, false), per_plane(*high, false)},
            380.0, kColours);
  return svg + "</svg>\n";
}

}  // namespace

Result<SpifPlacementResult> run_spif_placement_job(const Machine& machine, const SpifPlacementJob& job) {
  report_progress(job.progress, "reading the program");
  auto program = load_program_for(machine, job.program_path, job.program_options);
  if (!program) return program.error();
  report_progress(job.progress, "the drive energy at every height");
  auto placements = redundancy::placement_study(*program, machine, job.placement);
  if (!placements) return placements.error();
  const bool any =
      std::any_of(placements->begin(), placements->end(), [](const Placement& p) { return p.feasible; });
  if (!any) {
    const Placement& first = placements->front();
    return make_error(ErrorCode::unreachable,
                      fmt::format("{}:{}: at no height asked is the whole path within the machine's reach "
                                  "(at Z{:g} it leaves it here)",
                                  job.program_path, first.first_infeasible_line, first.z1_mm));
  }
  SpifPlacementResult result{std::move(*placements), {}};
  result.summary = summary_json(machine, job, result.placements);
  if (job.out_directory.empty()) return result;
  OutputSet outputs{"spif placement"};
  if (Status s = outputs.use_directory(job.out_directory); !s) return s.error();
  for (const auto& [name, text] :
       {std::pair<std::string, std::string>{"placement.csv", placement_csv(result.placements)},
        {"placement.svg", placement_svg(result.placements)},
        {"summary.json", json_text(result.summary) + "\n"}}) {
    if (Status written = write_file_atomically(outputs.staged_path(name), text); !written)
      return written.error();
  }
  if (Status committed = outputs.commit(); !committed) return committed.error();
  result.summary["out"] = job.out_directory;
  return result;
}

}  // namespace pkm::pipeline
