#pragma once
// `pkm spif placement` as one library call: the placement study of a forming program
// (redundancy/placement_study.hpp) at a range of heights, and its files: DIR/placement.csv (the energy of
// every plane at every height), DIR/placement.svg (the energy against the height,
// and per plane at the lowest and the highest) and DIR/summary.json, written as one set.
#include <nlohmann/json.hpp>
#include <string>

#include "core/progress.hpp"
#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"
#include "redundancy/placement_study.hpp"

namespace pkm::pipeline {

struct SpifPlacementJob {
  std::string program_path;
  ProgramOptions program_options;
  redundancy::PlacementOptions placement;
  std::string load_text;      ///< as given (--load), for the summary
  std::string out_directory;  ///< empty: nothing written
  ProgressSink progress;
};

struct SpifPlacementResult {
  std::vector<redundancy::Placement> placements;
  nlohmann::json summary;
};

/// Fails (ErrorCode::unreachable, naming the program line) when no height puts the whole path in reach.
Result<SpifPlacementResult> run_spif_placement_job(const Machine& machine, const SpifPlacementJob& job);

}  // namespace pkm::pipeline
