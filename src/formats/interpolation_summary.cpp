#include "formats/interpolation_summary.hpp"

#include <string>

#include "core/units.hpp"

namespace pkm::formats {

nlohmann::json interpolation_summary_json(const interpolation::InterpolateSummary& summary,
                                          const Machine& machine) {
  const int n = summary.actuators;
  const bool angular = machine.mechanism->actuators_are_angles();
  const double scale = angular ? deg_from_rad(1.0) : 1.0;
  const double step = angular ? rad_from_deg(summary.step_mm) : summary.step_mm;
  nlohmann::json actuators = nlohmann::json::array();
  for (int j = 0; j < n; ++j) {
    const double net_steps = static_cast<double>(summary.end_position[j] - summary.start_position[j]);
    const double ideal_net = step > 0.0 ? (summary.ideal_end[j] - summary.ideal_start[j]) / step : 0.0;
    actuators.push_back({{"start_position_steps", summary.start_position[j]},
                         {"end_position_steps", summary.end_position[j]},
                         {"net_steps", net_steps},
                         {"ideal_net_steps", ideal_net},
                         {"ideal_start", summary.ideal_start[j] * scale},
                         {"ideal_end", summary.ideal_end[j] * scale}});
  }
  const interpolation::ContourStatistics& c = summary.contour;
  nlohmann::json json = {
      {"machine", machine.source},
      {"method", std::string(interpolation::to_string(summary.method))},
      {"period_ms", summary.period_s * 1e3},
      {"step_" + std::string(angular ? "deg" : "mm"), summary.step_mm},
      {"rho_max_mm", summary.rho_max_mm},
      {"delta_rho_max", summary.delta_rho_max},
      {"delta_rho_max_line", summary.delta_rho_max_line},
      {"strut_tolerance_" + std::string(angular ? "deg" : "mm"), summary.strut_tolerance * scale},
      {"periods", summary.periods},
      {"ideal_time_s", summary.ideal_time_s},
      {"real_time_s", summary.real_time_s},
      {"max_contour_error_mm", c.max_error_mm},
      {"max_contour_error_line", c.max_error_line},
      {"max_contour_error_time_s", c.max_error_time_s},
      {"max_contour_error_after_first_period_mm", c.max_error_after_first_mm},
      {"max_period_end_contour_error_mm", c.max_period_end_error_mm},
      {"rms_contour_error_mm", c.rms_error_mm},
      {"start_error_mm", c.start_error_mm},
      {"end_error_mm", c.end_error_mm},
      {"max_orientation_error_deg", c.max_rotation_deg},
      {"contour_evaluations", c.evaluations},
      {"fk_failures", c.fk_failures},
      {"fk_solves_per_period", summary.fk_solves_per_period},
      {"jacobians_per_period", summary.jacobians_per_period},
      {"max_compute_us_per_period", summary.max_compute_us_per_period},
      {"mean_compute_us_per_period", summary.mean_compute_us_per_period},
      {"period_time_count", summary.period_time.count},
      {"period_time_us_p50", summary.period_time.p50_us},
      {"period_time_us_p99", summary.period_time.p99_us},
      {"period_time_us_p99_9", summary.period_time.p99_9_us},
      {"period_time_us_max", summary.period_time.max_us},
      {"period_time_us_mean", summary.period_time.mean_us},
      {"period_time_over_10us", summary.period_time.over_budget},
      {"max_steps_per_period", summary.max_steps_per_period},
      {"max_steps_line", summary.max_steps_line},
      {"max_remainder_steps", summary.max_remainder_steps},
      {"chord_reduced_periods", summary.carrier.chord_reduced_periods},
      {"drive_reduced_periods", summary.carrier.drive_reduced_periods},
      {"max_chord_error", summary.carrier.max_chord_error * scale},
      {"actuators", actuators},
  };
  if (summary.method != interpolation::Method::estimating) {
    json["strut_laws"] = {{"pieces", summary.laws.pieces},
                          {"exact", summary.laws.exact},
                          {"sqrt_quadratic", summary.laws.sqrt_quadratic},
                          {"sqrt_fourier", summary.laws.sqrt_fourier},
                          {"polynomial", summary.laws.polynomial},
                          {"max_fit_error", summary.laws.max_fit_error * scale},
                          {"max_fit_error_line", summary.laws.max_fit_error_line}};
  }
  if (summary.method == interpolation::Method::carrier_corrected) {
    json["correction"] = {{"fallbacks", summary.corrector.fallbacks},
                          {"max_predicted_error_mm", summary.corrector.max_predicted_error_mm}};
  }
  if (summary.method == interpolation::Method::estimating) {
    const interpolation::EstimatingStatistics& e = summary.estimating;
    json["estimating"] = {
        {"tacts", e.tacts},
        {"candidates", e.candidates},
        {"fk_solves", e.fk_solves},
        {"fallbacks", e.fallbacks},
        {"max_deviation_mm", e.max_deviation_mm},
        {"max_deviation_line", e.max_deviation_line},
        {"tacts_per_period", summary.periods > 0 ? static_cast<double>(e.tacts) / summary.periods : 0.0}};
  }
  return json;
}

}  // namespace pkm::formats
