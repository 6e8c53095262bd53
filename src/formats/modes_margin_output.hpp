#pragma once
// What `pkm modes-margin` writes and prints (docs/cli.md): the CSV of the samples along the program and the
// JSON summary. Margins are in the actuators' user unit: mm, or degrees for angular actuators (the columns
// and keys say which: `margin_mm` or `margin_deg`).
#include <nlohmann/json.hpp>
#include <string>

#include "machine/machine.hpp"
#include "workspace/modes_margin_program.hpp"

namespace pkm::formats {

/// "mm" or "deg": the unit margins are shown in.
const char* margin_unit(const Mechanism& mechanism);
/// A margin (mm, or rad for angular actuators) in that unit.
double margin_in_user_unit(const Mechanism& mechanism, double margin);

/// "found", "bound" (an upper bound: the search kept leaving the pose's aspect) or "none".
const char* margin_status(const workspace::AssemblyModeMargin& margin);

/// One row per sample: time_s, line, the pose columns of `--pose` (x_mm … in degrees), margin_status,
/// margin_mm (or margin_deg), det_ratio, the singular pose found (the pose columns prefixed `singular_`),
/// real_modes, other_mode_mm, other_mode_deg. Cells without a value are empty.
std::string modes_margin_csv(const Mechanism& mechanism, const workspace::ProgramModesMargin& result);

/// The summary: "kind": "modes_margin", machine and program files, duration, samples, the smallest and the
/// largest margin with line, time, pose and the singular pose, the nearest other mode with line, time, pose
/// and distances, and the real mode counts (null where there are none, with `modes_note` saying why).
nlohmann::json modes_margin_summary_json(const Machine& machine, const workspace::ProgramModesMargin& result);

}  // namespace pkm::formats
