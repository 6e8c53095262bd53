#pragma once
// The dynamics figures of a `pkm plan --dynamics` run for the report's summary table and its "limits
// reached", from the summary's "dynamics" block (docs/dynamics.md, docs/dynamics_elastic.md): the summary
// already holds the peaks over every tick with their program lines, so the report shows those rather than the
// plots' buckets.
#include <nlohmann/json.hpp>
#include <optional>

namespace pkm::report {

/// Rows of the summary table: peak force per drive with its line, peak power, the energy in each accounting,
/// and, for an elastic run, the lowest natural frequency and the largest dynamic tool error with its line.
/// Nothing when the summary has no dynamics block.
nlohmann::json dynamics_table_rows(const nlohmann::json& summary);

/// A drive whose peak force comes within 1 % of `force_limit_N` (the machine's actuator_force_max; a run
/// above it stops without output, so only "reached" occurs): entries for the report's "limits_reached".
nlohmann::json dynamics_limit_entries(const nlohmann::json& summary,
                                      const std::optional<double>& force_limit_N);

}  // namespace pkm::report
