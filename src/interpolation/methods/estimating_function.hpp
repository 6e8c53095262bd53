#pragma once
// The estimating-function interpolation method for a PKM (Smirnov 2019, §5.2.1), as a reference
// and offline interpolator: the drives hold whole steps q_j (actuator value q_j·Δ), and every tact moves
// some of them by one step, chosen by examining candidate moves with forward kinematics.
//
// Per tact (the publication's final 5-step procedure, §5.2.1):
//  1. candidates: every actuator −1/0/+1 step as the candidate set allows (estimating_candidates.hpp); FK of
//     each, warm-started from the current pose (a hexapod reuses one factorisation for all of them);
//  2. deviation criterion (§5.2.1, Fig. 148/155): the controlled point's distance from the path ≤ δ_allowed;
//  3. progress criterion (§5.2.1, Fig. 147/156): the increase of the nearest path point's parameter s is ≥ Δ
//     (the final rule) or > 0 (the first one);
//  4. selection: the largest progress (fewest tacts), or with `minimise_orientation` the least angle between
//     the platform's and the path's orientation (eq. 143, as a rotation angle), ties to the larger progress;
//  5. every actuator steps in its candidate's direction; the candidate's pose is the next tact's start.
// Smirnov 2019 measures against the straight line O_H → O_K; here the line is the whole program's path, with
// deviation and progress taken at the nearest path point (estimating_projection.hpp), so arcs and blends
// work the same way ("can be built in the same way", §5.2.1).
//
// What the publication leaves open (§5.2.1), decided here:
//  - fallback: greedy selection can dead-end (no candidate within δ makes progress; δ = 0.006 mm on the test
//    hexapod after about 10 tacts). Then the candidate with positive progress and the least deviation is
//    taken, or, if none progresses, the one with the least deviation; such tacts are counted. After
//    `max_stall_tacts` tacts in a row without admissible progress the run stops with an error naming the
//    program line and the position;
//  - end: once the remaining path is shorter than the typical progress per tact, the candidate nearest the
//    path's end point is taken, and the run ends when even that one would not come closer; the end error is
//    the distance from the end point;
//  - start: the start pose's actuator values are truncated to whole steps (toward zero, as in the
//    §5.2.5 example), so the start already deviates (4.9166e-4 mm on the ch5 line at Δ = 0.001 mm).
//
// Cost (§5.2.1): one FK per candidate, 64 per tact for all_six; the publication does not recommend the method
// for real-time control, hence its use here as a reference (bench/bench_estimating.cpp measures a tact).
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "interpolation/methods/estimating_candidates.hpp"
#include "interpolation/methods/estimating_projection.hpp"
#include "machine/machine.hpp"
#include "path/path.hpp"

namespace pkm::interpolation {

struct EstimatingSettings {
  double step_mm = 0.01;       ///< Δ, drive resolution (mm per step; rad for angular actuators)
  double deviation_mm = 0.01;  ///< δ_allowed
  CandidateSet candidates = CandidateSet::all_six;
  int struts_per_tact = 6;             ///< for exactly_k
  bool progress_at_least_step = true;  ///< progress ≥ Δ (true) or > 0 (false)
  bool minimise_orientation = false;   ///< eq. 143 secondary criterion
  /// Tacts in a row without admissible progress (fallbacks) before the run stops with an error; 0: stop at
  /// the first dead end (the publication's bare greedy rule).
  int max_stall_tacts = 1000;
  FkOptions fk;  ///< forward kinematics of every candidate
};

struct Tact {
  std::array<std::int8_t, kMaxActuators> direction{};  ///< −1, 0, +1 step per actuator in this tact
  double s = 0.0;             ///< path parameter of the nearest path point after the tact
  double deviation_mm = 0.0;  ///< perpendicular deviation after the tact
  bool fallback = false;      ///< no candidate met both criteria (or, at the end, the deviation one)
  double progress_mm = 0.0;   ///< increase of s in this tact (negative only in a fallback or at the end)
  double rotation_deviation_rad = 0.0;  ///< angle between the platform's and the path's orientation
  int moved = 0;                        ///< actuators that stepped
  bool end_approach = false;            ///< chosen by its distance to the path's end point
};

struct EstimatingStatistics {
  long tacts = 0;
  long candidates = 0;  ///< candidates examined (Table 5's "candidates total")
  long fk_solves = 0;
  long fallbacks = 0;
  double max_deviation_mm = 0.0;  ///< over the tacts, fallbacks included (the start: start_error_mm)
  int max_deviation_line = 0;     ///< program line where it occurred
  double start_error_mm = 0.0;    ///< deviation of the whole-step start pose from the path
  double end_error_mm = 0.0;      ///< distance from the path's end point, set when the run has finished
  double max_rotation_deviation_rad = 0.0;  ///< over the tacts (0 if the mechanism sets no orientation)
  long fk_failures = 0;                     ///< candidates whose FK failed (singular, other assembly mode)
  long out_of_range = 0;                    ///< candidates beyond an actuator limit (not solved)
};

class EstimatingInterpolator {
 public:
  /// Keeps references to `machine` and `path`; `source` (the program's name) prefixes messages.
  EstimatingInterpolator(const Machine& machine, const path::Path& path, const EstimatingSettings& settings,
                         std::string source);

  /// Rounds the start pose's actuator values to whole steps; error if the start is out of reach.
  Status start();
  /// The next tact; false at the end of the path or on error (then error() is set). No allocation per tact
  /// after start().
  bool next(Tact& tact);
  const std::optional<Error>& error() const { return error_; }
  const std::array<std::int64_t, kMaxActuators>& position_steps() const { return steps_; }  ///< current steps
  const Pose& pose() const { return pose_; }  ///< FK of the current positions
  const EstimatingStatistics& statistics() const { return statistics_; }
  double s() const { return s_; }  ///< path parameter of the current pose's nearest path point
  bool finished() const { return finished_; }

 private:
  /// One examined candidate, as the selection keeps it.
  struct Candidate {
    int index = -1;  ///< into directions_; −1 = none yet
    Pose pose;
    EstimatingNearest nearest;
    double progress_mm = 0.0;
    double rotation_rad = 0.0;
    double end_distance_mm = 0.0;
    bool found() const { return index >= 0; }
  };

  /// The best candidates of a tact by each rule.
  struct Candidates {
    Candidate admissible;  ///< best candidate meeting both criteria
    Candidate advancing;   ///< fallback: least deviation among those with positive progress
    Candidate closest;     ///< fallback: least deviation
    Candidate end_within;  ///< end zone: nearest the end point among those within δ
    Candidate end_any;     ///< end zone: nearest the end point
  };
  bool solve(const ActuatorVector& actuators, Pose& pose);
  /// Candidate `c`'s pose and where it is on the path; false (counted) out of range or without FK.
  bool evaluate(int c, ActuatorVector& actuators, Candidate& candidate);
  void rank(Candidate& candidate, bool end_zone, Candidates& best);
  bool finish_end_zone(const Candidates& best, Tact& tact);
  bool take_best(const Candidates& best, Tact& tact);
  double rotation_deviation(const Pose& pose, const EstimatingNearest& nearest) const;
  bool fail(ErrorCode code, const std::string& message, double s);
  void apply(const Candidate& chosen, bool fallback, bool end_approach, Tact& tact);

  const Machine& machine_;
  const path::Path& path_;
  EstimatingSettings settings_;
  std::string source_;
  std::unique_ptr<FkWorkspace> workspace_;  ///< the mechanism's FK state, made once by the constructor
  int actuators_ = 0;
  EstimatingProjector projector_;
  bool controls_orientation_ = true;
  double min_progress_mm_ = 0.0;
  std::vector<StepDirections> directions_;
  std::array<std::int64_t, kMaxActuators> steps_{};
  std::array<std::int64_t, kMaxActuators> min_steps_{};
  std::array<std::int64_t, kMaxActuators> max_steps_{};
  Pose pose_;
  double s_ = 0.0;
  double s_start_ = 0.0;
  double s_best_ = 0.0;  ///< the farthest s reached by an admissible tact (stall detection)
  double end_distance_mm_ = 0.0;
  int stall_tacts_ = 0;
  bool started_ = false;
  bool finished_ = false;
  std::optional<Error> error_;
  EstimatingStatistics statistics_;
};

}  // namespace pkm::interpolation
