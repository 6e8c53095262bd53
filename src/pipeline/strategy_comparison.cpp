#include "pipeline/strategy_comparison.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>

#include "io/atomic_file.hpp"
#include "io/output_set.hpp"
#include "path/surface_program.hpp"
#include "pipeline/plan_program.hpp"
#include "program/cl_writer.hpp"
#include "stiffness/strut_compliance.hpp"

namespace pkm::pipeline {
namespace {

namespace fs = std::filesystem;

// One entry of the comparison: a generated strategy (its program text) or a given program file.
struct ComparisonCase {
  std::string name;
  std::string program_text;  // generated: written to <name>/program.cl; empty for a given file
  std::string given_path;
};

// A given program's name in the table and its folder: the file's stem with anything but letters, digits,
// '-' and '_' replaced, made unique by a suffix.
std::string program_case_name(const std::string& path, const std::vector<ComparisonCase>& taken) {
  std::string stem = fs::path(path).stem().string();
  for (char& c : stem) {
    const bool plain =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    if (!plain) c = '_';
  }
  if (stem.empty()) stem = "program";
  auto used = [&taken](const std::string& name) {
    for (const ComparisonCase& c : taken)
      if (c.name == name) return true;
    return false;
  };
  std::string name = stem;
  for (int k = 2; used(name); ++k) name = fmt::format("{}_{}", stem, k);
  return name;
}

std::vector<std::string> cap_comments(const path::EllipsoidCap& cap, const path::StrategyOptions& options,
                                      path::SurfaceStrategy strategy) {
  const Eigen::Vector3d& s = cap.semi_axes_mm;
  const Eigen::Vector3d& c = cap.centre_mm;
  return {
      fmt::format("pkm strategies: {} over an ellipsoid cap", path::strategy_name(strategy)),
      fmt::format("semi-axes {} {} {} mm, centre {} {} {} mm, depth {} mm (largest tilt {:.2f} deg)", s.x(),
                  s.y(), s.z(), c.x(), c.y(), c.z(), cap.depth_mm,
                  path::cap_max_tilt_rad(cap) * 180.0 / std::numbers::pi),
      fmt::format(
          "step-over {} mm, point spacing {} mm on the surface; tool tip on the surface, tool axis "
          "on the normal (ball end); approach and retract are rapids, with a stop (DELAY/0) on the surface",
          options.step_over_mm, options.spacing_mm)};
}

// The error of a failed plan with the staging folder's name replaced by the output directory's, so that it
// names where the files would have been.
Error named_plan_error(Error error, const std::string& name, const std::string& staging,
                       const std::string& out_directory) {
  auto unstaged = [&](std::string text) {
    for (std::size_t at = text.find(staging); at != std::string::npos; at = text.find(staging, at))
      text.replace(at, staging.size(), out_directory), at += out_directory.size();
    return text;
  };
  error.message = fmt::format("strategy {}: {}", name, unstaged(error.message));
  error.location.file = unstaged(error.location.file);
  return error;
}

// The score of a planned run: the deflection summary (the table's errors are `pkm plan --stiffness`'s), the
// fed segments' length and moves, the cutting time.
StrategyScore score_of(const std::string& name, const std::string& program_path,
                       const PlanProgramResult& planned, FedSegments& fed) {
  StrategyScore score;
  score.name = name;
  score.program_path = program_path;
  std::set<int> fed_moves;
  for (const path::Segment& seg : planned.plan->path.segments) {
    if (seg.rapid) continue;
    if (!seg.rotation_only) score.path_length_mm += seg.length;
    if (!seg.is_blend()) fed_moves.insert(seg.move);
    fed.add(seg.line, seg.s_start, seg.s_start + seg.length);
  }
  score.points = static_cast<long>(fed_moves.size());
  if (planned.run.deflection) {
    const stiffness::DeflectionSummary& f = *planned.run.deflection;
    score.max_normal_mm = f.max_normal_mm;
    score.max_normal_line = f.max_normal_line;
    score.rms_normal_mm = f.rms_normal_mm;
    score.cutting_time_s = planned.run.motion.rate_hz > 0
                               ? static_cast<double>(f.cutting_points) / planned.run.motion.rate_hz
                               : 0.0;
  }
  return score;
}

Status check_comparison_job(const Machine& machine, const StrategyComparisonJob& job) {
  if (!job.surface && job.programs.empty())
    return make_error(ErrorCode::bad_input, "nothing to compare: give a surface or at least one program");
  if (job.surface) {
    if (Status valid = path::validate_strategy_options(*job.surface, job.strategy); !valid) return valid;
    if (!std::isfinite(job.feed_mm_min) || job.feed_mm_min <= 0.0)
      return make_error(ErrorCode::bad_input,
                        fmt::format("feed must be > 0 mm/min, got {}", job.feed_mm_min));
  }
  if (job.out_directory.empty()) return make_error(ErrorCode::bad_input, "no output directory given");
  if (auto stiffness = stiffness::strut_stiffness_of(machine); !stiffness) return stiffness.error();
  return ok_status();
}

// The programs of the job: the five strategies' CL text, then the given files. All made before anything is
// written, so that a bad input leaves no trace.
Result<std::vector<ComparisonCase>> comparison_cases(const StrategyComparisonJob& job) {
  std::vector<ComparisonCase> cases;
  if (job.surface) {
    path::SurfaceProgramOptions moves;
    moves.feed_mm_min = job.feed_mm_min;
    program::ClWriteOptions text;
    text.decimals_mm = 9;  // the points read back to 1e-9 mm
    text.decimals_axis = 12;
    for (const path::SurfaceStrategy strategy : path::kSurfaceStrategies) {
      auto generated = path::generate_strategy(strategy, *job.surface, job.strategy);
      if (!generated) return generated.error();
      text.header_comments = cap_comments(*job.surface, job.strategy, strategy);
      auto written = program::write_cl_data(path::surface_program(*generated, moves), text);
      if (!written) return written.error();
      cases.push_back({std::string(path::strategy_name(strategy)), std::move(*written), {}});
    }
  }
  for (const std::string& given : job.programs) cases.push_back({program_case_name(given, cases), {}, given});
  return cases;
}

struct ComparisonCaseResult {
  StrategyScore score;
  std::vector<ErrorMapPoint> map_sample;
};

// Plans one case into staging/<name>/ (its program.cl first, if generated) and adds its surface error map.
Result<ComparisonCaseResult> run_comparison_case(const Machine& machine, const StrategyComparisonJob& job,
                                                 const ComparisonCase& c, const std::string& staging,
                                                 const ProgressSink& progress) {
  const std::string run_directory = (fs::path(staging) / c.name).string();
  std::error_code failed;
  fs::create_directories(run_directory, failed);
  if (failed)
    return make_error(ErrorCode::io, fmt::format("cannot create {}: {}", run_directory, failed.message()));
  PlanJob plan;
  plan.program_path = c.given_path;
  if (c.given_path.empty()) {
    plan.program_path = (fs::path(run_directory) / "program.cl").string();
    if (Status written = write_file_atomically(plan.program_path, c.program_text); !written)
      return written.error();
  }
  plan.plan = job.plan;
  plan.evaluate_path_error = false;  // the comparison is about the load, not the interpolation
  plan.stiffness = true;
  plan.dynamics_load = job.load;
  plan.out_directory = run_directory;
  plan.progress = progress;
  plan.keep_plan = true;  // the score reads the whole path
  auto planned = plan_program(machine, plan);
  if (!planned) return named_plan_error(planned.error(), c.name, staging, job.out_directory);
  FedSegments fed;
  const std::string shown_program =
      c.given_path.empty() ? (fs::path(job.out_directory) / c.name / "program.cl").string() : c.given_path;
  ComparisonCaseResult result{score_of(c.name, shown_program, *planned, fed), {}};
  auto map = surface_error_map(run_directory, fed, job.map_points_in_plot);
  if (!map) return named_plan_error(map.error(), c.name, staging, job.out_directory);
  if (Status written =
          write_file_atomically((fs::path(run_directory) / "surface_error.csv").string(), map->csv);
      !written)
    return written.error();
  result.map_sample = std::move(map->sample);
  return result;
}

// Each run's files join the set as <name>/<file>; the folder <name> in DIR is made just before the renames
// and removed again if they fail (rmdir: only while empty).
Status commit_comparison(OutputSet& outputs, const std::vector<ComparisonCase>& cases,
                         const std::string& out_directory) {
  std::vector<std::string> made_directories;
  auto undo = [&made_directories] {
    for (const std::string& d : made_directories) ::rmdir(d.c_str());
  };
  for (const ComparisonCase& c : cases) {
    std::error_code failed;
    for (fs::directory_iterator it(fs::path(outputs.staging_directory()) / c.name, failed), end;
         !failed && it != end; it.increment(failed)) {
      if (it->is_regular_file()) outputs.staged_path(c.name + "/" + it->path().filename().string());
    }
    const std::string target = (fs::path(out_directory) / c.name).string();
    if (failed) {
      undo();
      return make_error(ErrorCode::io, fmt::format("cannot write {}: {}", target, failed.message()));
    }
    if (::mkdir(target.c_str(), 0777) == 0) {
      made_directories.push_back(target);
    } else if (errno != EEXIST) {
      const int error_number = errno;
      undo();
      return make_error(ErrorCode::io,
                        fmt::format("cannot create directory {}: {}", target,
                                    std::error_code(error_number, std::generic_category()).message()));
    }
  }
  if (Status committed = outputs.commit(); !committed) {
    undo();
    return committed;
  }
  return ok_status();
}

}  // namespace

Result<StrategyComparison> compare_strategies(const Machine& machine, const StrategyComparisonJob& job) {
  if (Status checked = check_comparison_job(machine, job); !checked) return checked.error();
  auto cases = comparison_cases(job);
  if (!cases) return cases.error();

  OutputSet outputs{"strategies"};
  if (Status used = outputs.use_directory(job.out_directory); !used) return used.error();
  std::vector<StrategyScore> scores;
  std::vector<std::vector<ErrorMapPoint>> maps;
  std::string phase;  // "NAME (k of N): the plan's phase", reused: the plan tells it every few thousand ticks
  for (const ComparisonCase& c : *cases) {
    const std::string label = fmt::format("{} ({} of {}): ", c.name, scores.size() + 1, cases->size());
    ProgressSink progress;
    if (job.progress) {
      progress = [&](const ProgressStep& step) {
        phase.assign(label).append(step.phase);
        job.progress(ProgressStep{phase, step.fraction, step.line, step.ticks});
      };
    }
    auto result = run_comparison_case(machine, job, c, outputs.staging_directory(), progress);
    if (!result) return result.error();
    scores.push_back(std::move(result->score));
    maps.push_back(std::move(result->map_sample));
  }

  // The table in the order run with the ranks of the sorted copy; the plot best first.
  StrategyComparison comparison{scores};
  rank_strategies(comparison.ranking);
  std::vector<std::vector<ErrorMapPoint>> ranked_maps;
  for (const StrategyScore& r : comparison.ranking) {
    for (std::size_t i = 0; i < scores.size(); ++i) {
      if (scores[i].name != r.name) continue;
      scores[i].rank = r.rank;
      ranked_maps.push_back(std::move(maps[i]));
    }
  }
  if (Status written = write_file_atomically(outputs.staged_path("strategies.csv"), strategies_csv(scores));
      !written)
    return written.error();
  if (Status written = write_file_atomically(outputs.staged_path("strategies.svg"),
                                             strategies_svg(comparison.ranking, ranked_maps));
      !written)
    return written.error();
  if (Status committed = commit_comparison(outputs, *cases, job.out_directory); !committed)
    return committed.error();
  return comparison;
}

}  // namespace pkm::pipeline
