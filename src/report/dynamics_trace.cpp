#include "report/dynamics_trace.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "report/report_data.hpp"

namespace pkm::report {

namespace {

enum Plot { kTotal, kStatic, kDynamic, kPower, kEnergy, kError };

/// The files' times have six decimals; a row of another tick is at least one servo period away.
constexpr double kSameTickS = 2e-6;

std::vector<std::string> names_with(const std::vector<std::string>& names, const std::string& extra) {
  std::vector<std::string> out = names;
  out.push_back(extra);
  return out;
}

}  // namespace

Status DynamicsTrace::open(const std::string& directory, formats::TickTables tables,
                           const nlohmann::json& summary, int drives, long expected_rows, int buckets) {
  if (!summary.contains("dynamics") || !summary["dynamics"].is_object()) return ok_status();
  const nlohmann::json& block = summary["dynamics"];
  drives_ = drives;
  auto forces = open_tick_table(directory, tables, "forces");
  if (!forces) return forces.error();
  forces_ = std::move(*forces);
  auto forces_time = forces_->require("time_s");
  if (!forces_time) return forces_time.error();
  forces_time_col_ = *forces_time;
  // Angular drives give torques in N·mm (P1_Nmm); the table's columns say which.
  const std::string unit = forces_->column("P1_Nmm") >= 0 ? "Nmm" : "N";
  force_unit_ = unit == "Nmm" ? "N·mm" : "N";
  for (int j = 1; j <= drives; ++j) {
    for (auto [name, columns] : {std::pair{fmt::format("P{}_{}", j, unit), &total_col_},
                                 std::pair{fmt::format("P{}_static_{}", j, unit), &static_col_},
                                 std::pair{fmt::format("P{}_dynamic_{}", j, unit), &dynamic_col_},
                                 std::pair{fmt::format("power{}_W", j), &power_col_}}) {
      auto index = forces_->require(name);
      if (!index) return index.error();
      columns->push_back(*index);
    }
  }
  elastic_ = block.contains("max_dynamic_tool_error_mm");
  if (elastic_) {
    auto response = open_tick_table(directory, tables, "response");
    if (!response) return response.error();
    response_ = std::move(*response);
    for (const char* name : {"tool_error_mm", "dx_mm", "dy_mm", "dz_mm"}) {
      auto index = response_->require(name);
      if (!index) return index.error();
      response_col_.push_back(*index);
    }
    auto time = response_->require("time_s");
    if (!time) return time.error();
    response_time_col_ = *time;
  }
  const double rate_hz = summary.value("rate_hz", 0.0);
  period_s_ = rate_hz > 0.0 ? 1.0 / rate_hz : 0.0;
  const auto n = static_cast<std::size_t>(drives);
  total_.assign(n, 0.0);
  static_part_.assign(n, 0.0);
  dynamic_part_.assign(n, 0.0);
  power_.assign(n + 1, 0.0);
  energy_J_.assign(3, 0.0);
  error_.assign(response_col_.size(), 0.0);
  for (int series : {drives, drives, drives, drives + 1, 3, static_cast<int>(error_.size())})
    plots_.emplace_back(series, expected_rows, buckets);
  active_ = true;
  return ok_status();
}

Status DynamicsTrace::next(double time_s, double s_mm) {
  if (!active_) return ok_status();
  auto more = forces_->next(row_);
  if (!more) return more.error();
  const double file_time_s = *more ? row_[static_cast<std::size_t>(forces_time_col_)] : 0.0;
  if (!*more || std::abs(file_time_s - time_s) > kSameTickS) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{}: not the tick at {:.6f} s of the path (a different run?)",
                                  forces_->where(*more ? 0 : 1), time_s));
  }
  const double h = period_s_ > 0.0 ? period_s_ : rows_ > 0 ? time_s - previous_time_s_ : 0.0;
  double sum_W = 0.0;
  for (int j = 0; j < drives_; ++j) {
    const auto J = static_cast<std::size_t>(j);
    total_[J] = row_[static_cast<std::size_t>(total_col_[J])];
    static_part_[J] = row_[static_cast<std::size_t>(static_col_[J])];
    dynamic_part_[J] = row_[static_cast<std::size_t>(dynamic_col_[J])];
    power_[J] = row_[static_cast<std::size_t>(power_col_[J])];
    // The summary's three accountings (dynamics/run_dynamics.hpp), summed per servo period as it does.
    energy_J_[0] += std::abs(power_[J]) * h;
    energy_J_[1] += std::max(0.0, power_[J]) * h;
    sum_W += power_[J];
  }
  energy_J_[2] += std::max(0.0, sum_W) * h;
  power_.back() = sum_W;
  plots_[kTotal].add(time_s, s_mm, total_.data());
  plots_[kStatic].add(time_s, s_mm, static_part_.data());
  plots_[kDynamic].add(time_s, s_mm, dynamic_part_.data());
  plots_[kPower].add(time_s, s_mm, power_.data());
  plots_[kEnergy].add(time_s, s_mm, energy_J_.data());
  if (elastic_) {
    auto response = response_->next(row_);
    if (!response) return response.error();
    if (!*response || std::abs(row_[static_cast<std::size_t>(response_time_col_)] - time_s) > kSameTickS) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}: not the tick at {:.6f} s of the path (a different run?)",
                                    response_->where(*response ? 0 : 1), time_s));
    }
    for (std::size_t k = 0; k < error_.size(); ++k)
      error_[k] = row_[static_cast<std::size_t>(response_col_[k])];
    plots_[kError].add(time_s, s_mm, error_.data());
  }
  previous_time_s_ = time_s;
  ++rows_;
  return ok_status();
}

Status DynamicsTrace::finish() {
  if (!active_) return ok_status();
  for (TableRows* table : {forces_.get(), response_.get()}) {
    if (table == nullptr) continue;
    auto more = table->next(row_);
    if (!more) return more.error();
    if (*more) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}: more rows than the path (a different run?)", table->where()));
    }
  }
  for (MinMaxDecimator& plot : plots_) plot.finish();
  return ok_status();
}

double DynamicsTrace::peak_force() const {
  double peak = 0.0;
  if (!active_) return peak;
  for (int j = 0; j < drives_; ++j) peak = std::max(peak, plots_[kTotal].peak(j));
  return peak;
}

nlohmann::json DynamicsTrace::charts(const std::optional<double>& force_limit) const {
  nlohmann::json charts = nlohmann::json::array();
  if (!active_) return charts;
  // Named as the forces table names the drives' forces (P1_N …) and powers (power1_W …).
  const nlohmann::json limits = plus_minus_lines(force_limit, force_unit_);
  charts.push_back(chart_json("drive_forces", "Drive forces (positive: the drive pushes)", "force",
                              force_unit_, plots_[kTotal], drive_names("P", drives_), true, limits));
  charts.push_back(chart_json("drive_forces_static", "Drive forces: static part (gravity and load)", "force",
                              force_unit_, plots_[kStatic], drive_names("P", drives_, " static"), true));
  charts.push_back(chart_json("drive_forces_dynamic", "Drive forces: dynamic part (inertia)", "force",
                              force_unit_, plots_[kDynamic], drive_names("P", drives_, " dynamic"), true));
  charts.push_back(chart_json("drive_power", "Drive power (negative: the drive brakes)", "power", "W",
                              plots_[kPower], names_with(drive_names("power ", drives_), "total"), true));
  charts.push_back(chart_json("drive_energy", "Drive energy drawn so far", "energy", "J", plots_[kEnergy],
                              {"no recovery", "braking free", "recovery"}, true));
  if (elastic_) {
    charts.push_back(chart_json("dynamic_error",
                                "Dynamic tool error (elastic machine from the commanded pose)", "error", "mm",
                                plots_[kError], {"|d|", "dx", "dy", "dz"}, true));
  }
  return charts;
}

}  // namespace pkm::report
