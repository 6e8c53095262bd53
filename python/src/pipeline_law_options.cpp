#include "pipeline_law_options.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm::python {

Result<statics::LoadModel> load_model(const std::string& spec) {
  if (spec.empty()) return statics::LoadModel{};
  auto loads = statics::parse_load_spec(spec);
  if (!loads) return make_error(loads.error().code, "load: " + loads.error().message);
  return loads;
}

Result<redundancy::OptimizeOptions> optimize_options(const LawArguments& a) {
  redundancy::OptimizeOptions options;
  const auto law = redundancy::law_from_string(a.law);
  if (!law)
    return make_error(
        ErrorCode::bad_input,
        fmt::format("law '{}': expected increment, force, energy, rotation or potential", a.law));
  options.law.law = *law;
  const auto free = redundancy::free_set_from_string(a.free);
  if (!free) return make_error(ErrorCode::bad_input, fmt::format("free '{}': expected spin or all", a.free));
  options.free = *free;
  const auto solver = redundancy::solver_from_string(a.solver);
  if (!solver)
    return make_error(ErrorCode::bad_input, fmt::format("solver '{}': expected greedy or global", a.solver));
  options.solver = *solver;
  const auto accounting = redundancy::energy_accounting_from_string(a.energy_accounting);
  if (!accounting) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("energy_accounting '{}': expected no-recovery, braking-free or recovery",
                                  a.energy_accounting));
  }
  options.law.energy = *accounting;
  const auto forces = redundancy::force_model_from_string(a.force_model);
  if (!forces) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("force_model '{}': expected statics or dynamics", a.force_model));
  }
  options.law.forces = *forces;
  for (const auto& range : a.bounds_deg) {
    if (!std::isfinite(range[0]) || !std::isfinite(range[1]))
      return make_error(ErrorCode::bad_input, "bounds_deg: expected finite angles (lo, hi) in degrees");
  }
  options.bounds_deg = a.bounds_deg;
  if (!(a.step_mm > 0.0 && a.step_mm <= 1000.0))
    return make_error(ErrorCode::bad_input,
                      fmt::format("step_mm {}: must be a length in (0, 1000] mm", a.step_mm));
  options.step_mm = a.step_mm;
  if (a.parts == "adaptive") {
    if (!(a.improvement >= 0.0 && a.improvement < 1.0))
      return make_error(ErrorCode::bad_input,
                        fmt::format("improvement {}: must be a share in [0, 1)", a.improvement));
    if (!(a.min_part_mm > 0.0 && a.min_part_mm <= 1000.0))
      return make_error(ErrorCode::bad_input,
                        fmt::format("min_part_mm {}: must be a length in (0, 1000] mm", a.min_part_mm));
    if (!(a.patience >= 1 && a.patience <= 1000))
      return make_error(ErrorCode::bad_input,
                        fmt::format("patience {}: must be a count in [1, 1000]", a.patience));
    options.subdivision = redundancy::SubdivisionSettings{a.improvement, a.min_part_mm};
    options.subdivision->patience = a.patience;
  } else if (a.parts != "fixed") {
    return make_error(ErrorCode::bad_input, fmt::format("parts '{}': expected fixed or adaptive", a.parts));
  }
  if (a.force_limit_N) {
    if (!(*a.force_limit_N > 0.0))
      return make_error(ErrorCode::bad_input, "force_limit_N must be a positive force in N");
    options.law.force_limit_N = *a.force_limit_N;
  }
  if (a.max_rate_deg_per_mm) {
    if (!(*a.max_rate_deg_per_mm > 0.0))
      return make_error(ErrorCode::bad_input, "max_rate_deg_per_mm must be a positive rate in deg/mm");
    options.whole_path.max_rate_deg_per_mm = *a.max_rate_deg_per_mm;
  }
  auto loads = load_model(a.load);
  if (!loads) return loads.error();
  options.loads = std::move(*loads);
  return options;
}

}  // namespace pkm::python
