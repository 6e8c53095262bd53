#include "formats/optimize_summary.hpp"

#include <cmath>

#include "core/units.hpp"

namespace pkm::formats {

namespace {

nlohmann::json metrics_json(const redundancy::TrajectoryMetrics& metrics, int free_count) {
  nlohmann::json json;
  json["feasible"] = metrics.feasible;
  if (!metrics.feasible) json["first_infeasible_line"] = metrics.first_infeasible_line;
  json["increment_sum_mm"] = metrics.increment_sum_mm;
  json["peak_force_N"] = metrics.peak_force_N;
  json["energy_J"] = metrics.energy_J;
  json["required_work_J"] = metrics.required_work_J;
  json["rotation_sum_deg"] = metrics.rotation_sum_deg;
  // null: the machine file gives no actuator range
  json["min_limit_margin"] =
      std::isfinite(metrics.min_limit_margin) ? nlohmann::json(metrics.min_limit_margin) : nlohmann::json();
  nlohmann::json range = nlohmann::json::array();
  for (int i = 0; i < free_count; ++i) {
    range.push_back({deg_from_rad(metrics.min_rad[i]), deg_from_rad(metrics.max_rad[i])});
  }
  json["range_deg"] = range;
  return json;
}

}  // namespace

nlohmann::json optimize_summary_json(const redundancy::OptimizeResult& result,
                                     const redundancy::OptimizeOptions& options) {
  const redundancy::TrajectoryMetrics& opt = result.chosen().metrics;
  const redundancy::TrajectoryMetrics& constant = result.constant;
  nlohmann::json json;
  json["program"] = result.program.source;
  json["law"] = redundancy::to_string(options.law.law);
  if (options.law.law == redundancy::Law::energy)
    json["energy_accounting"] = redundancy::to_string(options.law.energy);
  json["solver"] = options.solver == redundancy::Solver::global ? "global" : "greedy";
  json["force_model"] = redundancy::to_string(options.law.forces);
  json["free"] = redundancy::to_string(options.free);
  json["free_coordinates"] = result.free_names;
  nlohmann::json start = nlohmann::json::array();
  nlohmann::json bounds = nlohmann::json::array();
  for (int i = 0; i < result.free_count; ++i) {
    start.push_back(deg_from_rad(result.start_rad[i]));
    bounds.push_back({deg_from_rad(result.lower_rad[i]), deg_from_rad(result.upper_rad[i])});
  }
  json["start_deg"] = start;
  json["bounds_deg"] = bounds;
  json["points"] = result.points.points.size();
  json["step_mm"] = options.step_mm;
  json["parts"] = options.subdivision ? "adaptive" : "fixed";
  if (options.subdivision) {
    json["improvement"] = options.subdivision->improvement;
    json["min_part_mm"] = options.subdivision->min_part_mm;
    json["patience"] = options.subdivision->patience;
  }
  json["parts_written"] = result.parts_written;
  json["largest_parts"] = result.largest_parts;
  json["const_feasible"] = constant.feasible;
  json["const_sum_mm"] = constant.increment_sum_mm;
  json["opt_sum_mm"] = opt.increment_sum_mm;
  json["increment_ratio"] =
      opt.increment_sum_mm > 0.0 ? constant.increment_sum_mm / opt.increment_sum_mm : 1.0;
  json["peak_force_const_N"] = constant.peak_force_N;
  json["peak_force_opt_N"] = opt.peak_force_N;
  json["energy_const_J"] = constant.energy_J;
  json["energy_opt_J"] = opt.energy_J;
  json["required_work_J"] = opt.required_work_J;
  json["rotation_const_deg"] = constant.rotation_sum_deg;
  json["rotation_opt_deg"] = opt.rotation_sum_deg;
  json["free_range_deg"] = metrics_json(opt, result.free_count)["range_deg"];
  json["const"] = metrics_json(constant, result.free_count);
  json["greedy"] = metrics_json(result.greedy.metrics, result.free_count);
  json["greedy"]["seconds"] = result.greedy.seconds;
  if (result.whole_path) {
    json["whole_path"] = metrics_json(result.whole_path->metrics, result.free_count);
    json["whole_path"]["seconds"] = result.whole_path->seconds;
  }
  return json;
}

}  // namespace pkm::formats
