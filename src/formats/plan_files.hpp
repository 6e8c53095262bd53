#pragma once
// The files of a planned run: DIR/actuators.csv (time and every actuator position per servo tick),
// DIR/path.csv (commanded tool pose per tick, program coordinates, with the source line), DIR/summary.json,
// and for the analyses that listened DIR/forces.csv (drive forces: total, static, dynamic; drive power),
// DIR/response.csv (the elastic machine's deviation from the commanded pose) and DIR/deflection.csv (the
// tool's deflection under the process load). The files join an OutputSet (io/output_set.hpp): they replace
// the previous run's only together, when the whole run succeeded, so a failed run leaves the previous run
// complete and nothing of its own. With TickTables::hdf5 the five servo-rate tables are the groups actuators,
// path, forces, response and deflection of DIR/ticks.h5 instead (formats/plan_tables.hpp), the same columns.
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "analyses/plan_analyses.hpp"
#include "formats/hdf5_table.hpp"
#include "formats/plan_tables.hpp"
#include "io/buffered_file.hpp"
#include "io/output_set.hpp"
#include "machine/machine.hpp"
#include "planning/motion_plan.hpp"
#include "planning/tick_observer.hpp"

namespace pkm::formats {

/// G-code's A B C (degrees) of a rotation, computed again only when the rotation changes: a 3-axis program
/// keeps one orientation for millions of ticks, and the angles cost as much as the rest of the row.
class AbcOfRotation {
 public:
  const Eigen::Vector3d& of(const Eigen::Matrix3d& rotation);

 private:
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d abc_deg_ = Eigen::Vector3d::Zero();
};

/// Listens to the ticks of a run (actuators.csv, path.csv) and, through analysis_sinks(), to its analyses.
class PlanFiles final : public planning::TickObserver {
 public:
  PlanFiles(const Machine& machine, const analyses::PlanAnalysisOptions& analyses,
            TickTables tables = TickTables::csv);
  PlanFiles(const PlanFiles&) = delete;
  PlanFiles& operator=(const PlanFiles&) = delete;

  /// Stages the files in `outputs` (which must have its directory) and writes their header rows.
  Status open(OutputSet& outputs);
  Status on_tick(const planning::ServoTick& tick, const planning::RunMonitor& monitor) override;
  /// The rows of forces.csv, response.csv and deflection.csv, for the analyses the options named.
  analyses::PlanAnalysisSinks analysis_sinks();
  /// Writes summary.json and completes every file in the set (which the caller commits).
  Status finish(const nlohmann::json& summary);

 private:
  Status open_hdf5(OutputSet& outputs);
  Status on_tick_hdf5(const planning::ServoTick& tick, const planning::RunMonitor& monitor);
  analyses::PlanAnalysisSinks hdf5_sinks();
  Status finish_hdf5();
  const Machine& machine_;
  analyses::PlanAnalysisOptions analyses_;
  TickTables tables_;
  int actuators_ = 0;
  bool angular_ = false;
  bool commands_ = false;  // the drives are not ideal: forces has their commands too
  BufferedStagedFile actuators_csv_, path_csv_, summary_file_, forces_csv_, response_csv_, deflection_csv_;
  std::optional<Hdf5File> ticks_h5_;
  Hdf5Table actuators_h5_, path_h5_, forces_h5_, response_h5_, deflection_h5_;
  std::vector<double> row_;  // one row of the widest table, reused
  AbcOfRotation abc_;
};

/// A tick's row of the path table (path_columns(): time, line, s, x y z, A B C, speed, feed cap, path error;
/// NaN where the error was not evaluated) into out[0 … kPathColumns − 1]. `abc` keeps the angles of the
/// rotation before.
inline constexpr int kPathColumns = 12;
void path_values(const planning::ServoTick& tick, const planning::RunMonitor& monitor, const Machine& machine,
                 AbcOfRotation& abc, double* out);

/// summary.json of a planned run (units in the key names): the motion, the machine's limits and warnings,
/// and a "dynamics" and a "stiffness" block for the analyses that listened.
nlohmann::json plan_summary_json(const planning::MotionPlan& plan, const Machine& machine,
                                 const analyses::PlanRun& run);

}  // namespace pkm::formats
