#pragma once
// Calibration measurement files (docs/calibration.md): CSV with its units, frame and kind in `#
// key: value` lines before the column row. A laser tracker or CMM file (kind tracker) gives, per pose, the
// drive readings and the measured base-frame position of targets of the fixture (io/fixture_file.hpp):
//
//   # kind: tracker
//   # units: mm
//   # frame: base
//   # sigma_mm: 0.01
//   # fixture: plate.csv
//   pose_id,L1,L2,L3,L4,L5,L6,target,x,y,z
//   P1,623.79,607.55,603.12,586.31,588.59,621.64,A,123.2,100.1,549.9
//
// A ballbar file (kind ballbar, `# ballbar_centre_mm: x y z`) gives `pose_id,L1..Ln,distance`: the tool
// point's distance from the ball on the table. Either may add a `sigma` column (mm; empty: the `# sigma_mm`
// default). The rows of one pose repeat its readings; machines with angular actuators say `# actuator_units:
// deg|rad`. Every refusal names "FILE:LINE:COLUMN: KEY: reason", with the place also in Error::location.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "io/measurements.hpp"
#include "machine/machine.hpp"

namespace pkm {

/// What the reader checks the file against: the machine's actuators, and how many poses the caller needs.
struct MeasurementReadOptions {
  int actuator_count = 6;              ///< the columns L1..Ln must be exactly this many
  bool actuators_are_angles = false;   ///< readings in deg or rad (`# actuator_units`), else mm
  std::optional<double> actuator_min;  ///< the machine's travel (mm, or rad): readings beyond it are refused
  std::optional<double> actuator_max;
  int min_poses = 1;         ///< fewer distinct poses is an error
  std::string fixture_path;  ///< the fixture file; "" → the file's `# fixture:` (relative to the file)
};

/// The options for a machine: its actuator count, kind and travel.
MeasurementReadOptions measurement_options_for(const Machine& machine, int min_poses);

/// Loads the fixture a tracker file names (`name` as the `# fixture:` line gives it, or the caller's path).
using FixtureLoader = std::function<Result<std::vector<calibration::FixtureTarget>>(const std::string& name)>;

/// The measurements in `text`; `source` names it in messages. The fixture of a tracker file comes from
/// `load_fixture` (with options.fixture_path when set, else with the `# fixture:` value).
Result<calibration::MeasurementSet> parse_measurement_csv(std::string_view text, const std::string& source,
                                                          const MeasurementReadOptions& options,
                                                          const FixtureLoader& load_fixture);
/// The same with the fixture given (a `# fixture:` line is then only a name).
Result<calibration::MeasurementSet> parse_measurement_csv(
    std::string_view text, const std::string& source, const MeasurementReadOptions& options,
    const std::vector<calibration::FixtureTarget>& fixture);
/// A measurement file through the guarded reader; its fixture from options.fixture_path, else from its
/// `# fixture:` line relative to the file's folder.
Result<calibration::MeasurementSet> read_measurement_file(const std::string& path,
                                                          const MeasurementReadOptions& options);

/// How the writer states what the file does not carry in MeasurementSet.
struct MeasurementWriteOptions {
  bool actuators_are_angles = false;  ///< readings written in degrees (`# actuator_units: deg`)
  std::string fixture_file;           ///< the `# fixture:` line ("" none)
  std::string machine_file;           ///< the `# machine:` line, for the record ("" none)
  std::vector<std::string> notes;     ///< `# note:` lines (one line each)
};

/// The text of a measurement file that the reader gives back as `set` (numbers round-trip exactly; angles in
/// degrees to within rounding). Fails for names that cannot stand in the file (is_calibration_name) and for a
/// set that is empty or mixes kinds.
Result<std::string> measurement_file_text(const calibration::MeasurementSet& set,
                                          const MeasurementWriteOptions& options);

}  // namespace pkm
