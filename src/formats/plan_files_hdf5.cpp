// PlanFiles with TickTables::hdf5: the servo-rate tables as the groups of DIR/ticks.h5.
#include <utility>

#include "core/units.hpp"
#include "formats/plan_files.hpp"
#include "io/version.hpp"

namespace pkm::formats {

Status PlanFiles::open_hdf5(OutputSet& outputs) {
  auto file = Hdf5File::create(outputs.staged_path("ticks.h5"));
  if (!file) return file.error();
  ticks_h5_.emplace(std::move(*file));
  if (Status opened = summary_file_.open(outputs.staged_path("summary.json")); !opened) return opened;
  for (auto [name, value] :
       {std::pair{"pkm_version", std::string(pkm_version())}, std::pair{"machine", machine_.source}}) {
    if (Status set = ticks_h5_->set_attribute(name, value); !set) return set;
  }
  const bool elastic = analyses_.dynamics && analyses_.elastic;
  std::size_t widest = 0;
  for (auto [table, name, columns, wanted] :
       {std::tuple{&actuators_h5_, "actuators", actuator_columns(actuators_, angular_), true},
        std::tuple{&path_h5_, "path", path_columns(), true},
        std::tuple{&forces_h5_, "forces", force_columns(actuators_, angular_, commands_), analyses_.dynamics},
        std::tuple{&response_h5_, "response", response_columns(), elastic},
        std::tuple{&deflection_h5_, "deflection", deflection_columns(), analyses_.stiffness}}) {
    if (!wanted) continue;
    auto made = ticks_h5_->table(name, columns);
    if (!made) return made.error();
    *table = std::move(*made);
    widest = std::max(widest, columns.size());
  }
  row_.assign(widest, 0.0);
  return ok_status();
}

Status PlanFiles::on_tick_hdf5(const planning::ServoTick& tick, const planning::RunMonitor& monitor) {
  const double scale = angular_ ? deg_from_rad(1.0) : 1.0;
  row_[0] = tick.time_s;
  for (int j = 0; j < actuators_; ++j) row_[1 + j] = tick.actuators[j] * scale;
  if (Status kept = actuators_h5_.append(row_.data()); !kept) return kept;
  path_values(tick, monitor, machine_, abc_, row_.data());
  return path_h5_.append(row_.data());
}

analyses::PlanAnalysisSinks PlanFiles::hdf5_sinks() {
  analyses::PlanAnalysisSinks sinks;
  const int n = actuators_;
  if (analyses_.dynamics) {
    sinks.dynamics = [this, n](const dynamics::TickDynamics& t) -> Status {
      double* r = row_.data();
      *r++ = t.time_s;
      *r++ = t.line;
      for (int j = 0; j < n; ++j) {
        *r++ = t.forces.total[j];
        *r++ = t.forces.static_part[j];
        *r++ = t.forces.dynamic_part[j];
      }
      for (int j = 0; j < n; ++j) *r++ = t.power_W[j];
      for (int j = 0; j < n && commands_; ++j) *r++ = t.command_N[j];
      return forces_h5_.append(row_.data());
    };
  }
  if (analyses_.dynamics && analyses_.elastic) {
    sinks.elastic = [this](const dynamics::ElasticTick& t) -> Status {
      const double r[] = {t.time_s,           static_cast<double>(t.line), t.deviation_mm.x(),
                          t.deviation_mm.y(), t.deviation_mm.z(),          t.rotation_deg,
                          t.tool_error_mm};
      return response_h5_.append(r);
    };
  }
  if (analyses_.stiffness) {
    sinks.deflection = [this](const stiffness::DeflectionTick& t) -> Status {
      const double r[] = {t.time_s,
                          static_cast<double>(t.line),
                          t.deflection_mm.x(),
                          t.deflection_mm.y(),
                          t.deflection_mm.z(),
                          t.normal_mm,
                          t.rotation_rad};
      return deflection_h5_.append(r);
    };
  }
  return sinks;
}

Status PlanFiles::finish_hdf5() {
  const bool elastic = analyses_.dynamics && analyses_.elastic;
  for (auto [table, written] : {std::pair{&actuators_h5_, true}, std::pair{&path_h5_, true},
                                std::pair{&forces_h5_, analyses_.dynamics}, std::pair{&response_h5_, elastic},
                                std::pair{&deflection_h5_, analyses_.stiffness}}) {
    if (!written) continue;
    if (Status finished = table->finish(); !finished) return finished;
  }
  return ticks_h5_->close();
}

}  // namespace pkm::formats
