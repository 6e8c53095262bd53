#pragma once
// summary.json of an interpolation run (`pkm interpolate`): the method, the contour error, the drives' steps
// and the compute time per period; the keys carry their units.
#include <nlohmann/json.hpp>

#include "interpolation/interpolate_run.hpp"
#include "machine/machine.hpp"

namespace pkm::formats {

nlohmann::json interpolation_summary_json(const interpolation::InterpolateSummary& summary,
                                          const Machine& machine);

}  // namespace pkm::formats
