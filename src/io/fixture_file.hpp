#pragma once
// The fixture file of a calibration (docs/calibration.md): the targets fixed to the platform whose
// positions a tracker or CMM measures, in the tool frame (origin at the tool point, platform axes), mm:
//
//   # units: mm
//   # frame: tool
//   target,x,y,z
//   A,173.205,100,-150
//
// Both header lines are required, so that a file in inches or in the platform-joint frame is refused rather
// than read as something else. Errors name "FILE:LINE:COLUMN: KEY: reason".
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "io/measurements.hpp"

namespace pkm {

/// The targets of a fixture file's text; `source` names it in messages. At least one target, names unique.
Result<std::vector<calibration::FixtureTarget>> parse_fixture_csv(std::string_view text,
                                                                  const std::string& source);
/// The same for a file (through the guarded reader, io/input_file.hpp).
Result<std::vector<calibration::FixtureTarget>> read_fixture_file(const std::string& path);
/// The text of a fixture file that parse_fixture_csv reads back to the same targets (numbers round-trip).
std::string fixture_file_text(const std::vector<calibration::FixtureTarget>& targets);

/// Whether a name can stand in a calibration CSV file and in the JSON written from it: not empty, valid UTF-8
/// without control bytes, no comma, no '#' at its start and no blanks around it.
bool is_calibration_name(std::string_view name);

}  // namespace pkm
