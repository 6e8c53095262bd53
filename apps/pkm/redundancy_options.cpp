#include "redundancy_options.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "number_options.hpp"

namespace pkm::cli {

void add_redundancy_options(CLI::App& command, RedundancyArguments& arguments, bool law_required) {
  auto* law = command.add_option(
      "--law", arguments.law,
      "drive control law for the free coordinates: increment | force | energy | rotation | potential");
  if (law_required) law->required();
  command
      .add_option("--free", arguments.free,
                  "free coordinates: spin (about the tool axis; planar: phi) | all (every angle)")
      ->capture_default_str();
  command.add_option("--bounds", arguments.bounds,
                     "LO,HI bounds of every free coordinate, or LO,HI,LO,HI,LO,HI of each of three, degrees "
                     "(default: start ± 30)");
  command
      .add_option("--step-mm", arguments.step_mm,
                  "path step between optimised points, mm (adaptive parts: the step the criterion is "
                  "measured along each part)")
      ->capture_default_str()
      ->check(number_in({0.0, 1000.0, false, true, "mm"}));
  command
      .add_option("--parts", arguments.parts,
                  "fixed (every block cut into parts of --step-mm) | adaptive (each block cut into N = 1, 2, "
                  "... parts until a finer cut no longer pays, Smirnov 2019 3.6)")
      ->capture_default_str();
  command
      .add_option("--improvement", arguments.improvement,
                  "adaptive parts: a finer cut must lower the block's criterion by more than this share")
      ->capture_default_str()
      ->check(number_in({0.0, 1.0, true, false, ""}));
  command.add_option("--min-part-mm", arguments.min_part_mm, "adaptive parts: the shortest part, mm")
      ->capture_default_str()
      ->check(number_in({0.0, 1000.0, false, true, "mm"}));
  command
      .add_option("--patience", arguments.patience,
                  "adaptive parts: finer cuts in a row that may fail to pay before a block's search stops "
                  "(Smirnov 2019 stops at the first: 1)")
      ->capture_default_str()
      ->check(number_in({1.0, 1000.0, true, true, "", true}));
  command.add_option(
      "--load", arguments.load,
      "cutting load: key=value list (tangential, normal, axial, cutter_radius, contact, force, "
      "moment) or @FILE.yaml (docs/statics.md)");
  command
      .add_option("--solver", arguments.solver,
                  "greedy (step by step along the path, Smirnov 2019 ch. 3) | global (whole path)")
      ->capture_default_str();
  command
      .add_option("--energy-accounting", arguments.energy_accounting,
                  "energy law: no-recovery (Smirnov 2019 ch. 3) | braking-free | recovery")
      ->capture_default_str();
  command
      .add_option("--force-model", arguments.force_model,
                  "forces the laws see: statics (load and weights) | dynamics (the rigid dynamics "
                  "at the programmed feed; needs the machine's dynamics: section)")
      ->capture_default_str();
  command
      .add_option("--force-limit", arguments.force_limit_N,
                  "drive force limit, N: candidates over it are not admissible (0: none)")
      ->check(number_in({0.0, 1e9, true, true, "N"}));
  command
      .add_option("--max-rate", arguments.max_rate_deg_per_mm,
                  "global solver: largest change of a free coordinate per mm of path, deg/mm (0: none)")
      ->check(number_in({0.0, 1e6, true, true, "deg/mm"}));
}

namespace {

// As for --pose (io/pose_input.cpp): no free coordinate turns a million degrees.
constexpr double kMaxBoundDeg = 1e6;

bool parse_double(std::string_view text, double& value) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

}  // namespace

// --bounds LO,HI[,LO,HI,LO,HI] (degrees): pairs of finite numbers, each LO below its HI. from_chars reads
// "nan" and "inf" as numbers, and NaN fails every comparison: without the check "nan,nan" was refused as "the
// lower bound must be below".
Result<redundancy::FreeBounds> parse_bounds(const std::string& text) {
  std::vector<std::string_view> parts;
  for (std::size_t from = 0;;) {
    const std::size_t comma = text.find(',', from);
    parts.push_back(std::string_view(text).substr(from, comma == std::string::npos ? comma : comma - from));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  if (parts.size() != 2 && parts.size() != 6) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--bounds {}: expected LO,HI in degrees for every free coordinate, or "
                                  "LO,HI,LO,HI,LO,HI for each of three, e.g. --bounds 5,30",
                                  text));
  }
  redundancy::FreeBounds bounds(parts.size() / 2);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    double& value = bounds[i / 2][i % 2];
    const char* which = i % 2 == 0 ? "LO" : "HI";
    if (!parse_double(parts[i], value)) {
      return make_error(ErrorCode::bad_input, fmt::format("--bounds {}: {} '{}' is not a number in degrees",
                                                          text, which, parts[i]));
    }
    if (!std::isfinite(value) || std::abs(value) > kMaxBoundDeg) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("--bounds {}: {} '{}' is {}", text, which, parts[i],
                                    std::isfinite(value)
                                        ? fmt::format("out of range (at most {:g} deg in size)", kMaxBoundDeg)
                                        : std::string("not a number")));
    }
  }
  for (const auto& range : bounds) {
    if (!(range[0] < range[1])) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("--bounds {}: LO must be below HI (degrees), got {:g} and {:g}", text,
                                    range[0], range[1]));
    }
  }
  return bounds;
}

Result<redundancy::OptimizeOptions> redundancy_options(const RedundancyArguments& arguments) {
  redundancy::OptimizeOptions options;
  auto law = redundancy::law_from_string(arguments.law);
  if (!law) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("--law {}: expected increment, force, energy, rotation or potential", arguments.law));
  }
  options.law.law = *law;
  auto free = redundancy::free_set_from_string(arguments.free);
  if (!free)
    return make_error(ErrorCode::bad_input, fmt::format("--free {}: expected spin or all", arguments.free));
  options.free = *free;
  auto solver = redundancy::solver_from_string(arguments.solver);
  if (!solver) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--solver {}: expected greedy or global", arguments.solver));
  }
  options.solver = *solver;
  auto accounting = redundancy::energy_accounting_from_string(arguments.energy_accounting);
  if (!accounting) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--energy-accounting {}: expected no-recovery, braking-free or recovery",
                                  arguments.energy_accounting));
  }
  options.law.energy = *accounting;
  auto force_model = redundancy::force_model_from_string(arguments.force_model);
  if (!force_model) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--force-model {}: expected statics or dynamics", arguments.force_model));
  }
  options.law.forces = *force_model;
  if (!arguments.bounds.empty()) {
    auto bounds = parse_bounds(arguments.bounds);
    if (!bounds) return bounds.error();
    options.bounds_deg = *bounds;
  }
  if (!(arguments.step_mm > 0.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--step-mm {}: must be a positive length", arguments.step_mm));
  }
  options.step_mm = arguments.step_mm;
  if (arguments.parts == "adaptive") {
    options.subdivision = redundancy::SubdivisionSettings{arguments.improvement, arguments.min_part_mm};
    options.subdivision->patience = arguments.patience;
  } else if (arguments.parts != "fixed") {
    return make_error(ErrorCode::bad_input,
                      fmt::format("--parts {}: expected fixed or adaptive", arguments.parts));
  }
  if (arguments.force_limit_N < 0.0) {
    return make_error(ErrorCode::bad_input, "--force-limit must be a positive force in N (0: none)");
  }
  if (arguments.force_limit_N > 0.0) options.law.force_limit_N = arguments.force_limit_N;
  if (arguments.max_rate_deg_per_mm < 0.0) {
    return make_error(ErrorCode::bad_input, "--max-rate must be a positive rate in deg/mm (0: none)");
  }
  if (arguments.max_rate_deg_per_mm > 0.0)
    options.whole_path.max_rate_deg_per_mm = arguments.max_rate_deg_per_mm;
  if (!arguments.load.empty()) {
    auto loads = statics::parse_load_spec(arguments.load);
    if (!loads) return make_error(loads.error().code, "--load: " + loads.error().message);
    options.loads = std::move(*loads);
  }
  return options;
}

}  // namespace pkm::cli
