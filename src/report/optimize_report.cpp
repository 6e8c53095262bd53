#include "report/optimize_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/units.hpp"
#include "report/run_reports.hpp"
#include "report/scene.hpp"

namespace pkm::report {

namespace {

double metric_at(const std::vector<double>& values, std::size_t k) {
  return k < values.size() ? values[k] : std::numeric_limits<double>::quiet_NaN();
}

// Time at the programmed feed and path length at every point: the post-processor keeps the contour speed of
// every block.
void times_at_feed(const Machine& machine, const program::CanonicalProgram& program,
                   const std::vector<redundancy::PathPoint>& points, std::vector<double>& time_s,
                   std::vector<double>& s_mm) {
  time_s.assign(points.size(), 0.0);
  s_mm.assign(points.size(), 0.0);
  for (std::size_t k = 1; k < points.size(); ++k) {
    const int move = points[k].move_index;
    double feed_mm_s = machine.motion.rapid_mm_min / 60.0;
    if (move >= 0 && move < static_cast<int>(program.moves.size()) && points[k].cutting &&
        program.moves[static_cast<std::size_t>(move)].feed_mm_min > 0.0) {
      feed_mm_s = std::min(program.moves[static_cast<std::size_t>(move)].feed_mm_min,
                           machine.motion.max_feed_mm_min) /
                  60.0;
    }
    s_mm[k] = s_mm[k - 1] + points[k].step_mm;
    time_s[k] = time_s[k - 1] + points[k].step_mm / feed_mm_s;
  }
}

// The summary table: the law, and what it changed against the free coordinates held constant.
nlohmann::json optimize_table(const nlohmann::json& summary, const redundancy::OptimizeOptions& options,
                              const std::string& law, const std::string& unit, long count, bool loaded) {
  auto number = [&](const char* key) {
    return summary.contains(key) && summary[key].is_number() ? summary[key].get<double>()
                                                             : std::numeric_limits<double>::quiet_NaN();
  };
  nlohmann::json table = nlohmann::json::array();
  table.push_back(
      table_row("Law / free coordinates / solver",
                fmt::format("{} / {} / {}", law, to_string(options.free),
                            options.solver == redundancy::Solver::global ? "whole path" : "greedy")));
  table.push_back(
      table_row("Points / step", fmt::format("{} / {}", count, with_unit(options.step_mm, "mm"))));
  table.push_back(
      table_row("Σ max|ΔL| held constant → chosen",
                fmt::format("{} → {} ({:.1f} % of the time at strut speed limits)",
                            with_unit(number("const_sum_mm"), unit), with_unit(number("opt_sum_mm"), unit),
                            100.0 * number("opt_sum_mm") / number("const_sum_mm"))));
  if (loaded) {
    table.push_back(table_row("Peak force held constant → chosen",
                              fmt::format("{} → {}", with_unit(number("peak_force_const_N"), "N"),
                                          with_unit(number("peak_force_opt_N"), "N"))));
    table.push_back(table_row("Energy held constant → chosen",
                              fmt::format("{} → {}", with_unit(number("energy_const_J"), "J"),
                                          with_unit(number("energy_opt_J"), "J"))));
  } else {
    table.push_back(
        table_row("Strut forces and energy",
                  "no load and no masses: none (give a load file or the machine file's masses:)"));
  }
  return table;
}

// Each free coordinate twice: as the law chose it and held constant.
std::vector<std::string> free_angle_names(const redundancy::FreeCoordinates& free, int free_count) {
  std::vector<std::string> names;
  for (int i = 0; i < free_count; ++i) {
    names.push_back(free.name(i) + " chosen");
    names.push_back(free.name(i) + " held constant");
  }
  return names;
}

}  // namespace

Result<nlohmann::json> optimize_report(const Machine& machine, const program::CanonicalProgram& program,
                                       const redundancy::OptimizeResult& result,
                                       const redundancy::OptimizeOptions& options,
                                       const nlohmann::json& summary, const std::string& output_file,
                                       const ReportOptions& report_options) {
  auto free = redundancy::FreeCoordinates::create(*machine.mechanism, options.free, options.bounds_deg,
                                                  result.start_rad);
  if (!free) return free.error();
  const auto& points = result.points.points;
  const redundancy::SolverReport& chosen = result.chosen();
  const auto& values = chosen.trajectory.values;
  if (points.empty() || values.size() != points.size()) {
    return make_error(ErrorCode::bad_input, "optimize report: the result has no trajectory for its points");
  }
  const int free_count = result.free_count;
  const long count = static_cast<long>(points.size());
  std::vector<double> time_s, s_mm;
  times_at_feed(machine, program, points, time_s, s_mm);

  const int buckets = report_options.chart_buckets;
  MinMaxDecimator angles(2 * free_count, count, buckets), increments(2, count, buckets),
      forces(2, count, buckets), energy(2, count, buckets);
  SceneBuilder scene(machine, time_s.back(), count, report_options.frames, report_options.path_points);
  const ActuatorLimits limits = limits_in_file_units(machine);
  const double scale = machine.mechanism->actuators_are_angles() ? deg_from_rad(1.0) : 1.0;
  const int n = machine.mechanism->actuator_count();
  std::vector<double> closeness(static_cast<std::size_t>(n), 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < points.size(); ++k) {
    double a[6] = {nan, nan, nan, nan, nan, nan};
    for (int i = 0; i < free_count; ++i) {
      a[2 * i] = deg_from_rad(values[k][i]);
      a[2 * i + 1] = deg_from_rad(result.start_rad[i]);
    }
    angles.add(time_s[k], s_mm[k], a);
    const double inc[2] = {metric_at(chosen.metrics.max_increment_mm, k),
                           metric_at(result.constant.max_increment_mm, k)};
    increments.add(time_s[k], s_mm[k], inc);
    const double force[2] = {metric_at(chosen.metrics.max_force_N, k),
                             metric_at(result.constant.max_force_N, k)};
    forces.add(time_s[k], s_mm[k], force);
    const double joules[2] = {metric_at(chosen.metrics.cumulative_energy_J, k),
                              metric_at(result.constant.cumulative_energy_J, k)};
    energy.add(time_s[k], s_mm[k], joules);
    const Pose pose = free->pose(points[k], values[k]);
    scene.add_path_point(pose.position_mm, pose.position_mm, 0.0);
    if (scene.frame_due(time_s[k]) || k + 1 == points.size()) {
      if (k < chosen.trajectory.nodes.size() && chosen.trajectory.nodes[k].valid) {
        for (int j = 0; j < n; ++j) {
          closeness[static_cast<std::size_t>(j)] =
              limit_closeness(limits, chosen.trajectory.nodes[k].lengths[j] * scale, nan, nan);
        }
      }
      scene.add_frame(time_s[k], points[k].line, pose, closeness);
    }
  }
  for (auto* d : {&angles, &increments, &forces, &energy}) d->finish();

  const std::vector<std::string> angle_names = free_angle_names(*free, free_count);
  const std::string law(to_string(options.law.law));
  const std::string unit = actuator_unit(machine);
  nlohmann::json charts = nlohmann::json::array();
  charts.push_back(chart_json("free_coordinates",
                              "Free coordinates: chosen by the " + law + " law, and held constant", "angle",
                              "deg", angles, angle_names, true));
  charts.push_back(chart_json("strut_increments",
                              "Largest strut increment per step (∝ time at strut speed limits)", "increment",
                              unit, increments, {"chosen", "held constant"}, true));
  if (forces.peak(0) > 0.0 || forces.peak(1) > 0.0) {
    charts.push_back(chart_json("strut_forces", "Peak strut force", "force", "N", forces,
                                {"chosen", "held constant"}, true));
    charts.push_back(chart_json("energy", "Drive energy (cumulative)", "energy", "J", energy,
                                {"chosen", "held constant"}, true));
  }

  const bool loaded = forces.peak(0) > 0.0 || forces.peak(1) > 0.0;
  nlohmann::json table = optimize_table(summary, options, law, unit, count, loaded);
  table.push_back(table_row("Duration at the programmed feed", with_unit(time_s.back(), "s")));
  table.push_back(table_row("Output program", output_file));
  table.push_back(table_row("Program", program.source));
  table.push_back(table_row("Machine file", machine.source));
  nlohmann::json reached = nlohmann::json::array();
  if (!chosen.metrics.feasible) {
    reached.push_back({{"what", "the chosen coordinates leave the machine's limits"},
                       {"line", chosen.metrics.first_infeasible_line},
                       {"severity", "exceeded"}});
  }
  ReportParts parts;
  parts.kind = "optimize";
  parts.title = fmt::format("{} on {}: {} law", std::filesystem::path(program.source).filename().string(),
                            machine.name, law);
  parts.program_file = program.source;
  parts.table = std::move(table);
  parts.limits_reached = std::move(reached);
  parts.summary = summary;
  parts.charts = std::move(charts);
  return report_document(machine, std::move(parts), scene);
}

}  // namespace pkm::report
