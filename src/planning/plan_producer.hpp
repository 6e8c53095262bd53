#pragma once
// The plan made while the program is read, stage by stage: each canonical move extends the tool path
// (path/path_appender.hpp), its final segments are sampled (path_sampling.hpp), the samples' speeds come out
// of the bounded look-ahead window (lookahead_profile.hpp) and are timed. A consumer asks for the plan up to
// a time and releases what lies behind it, so the plan it holds is a window bounded by the look-ahead, not
// by the program: the plan is the same as the whole program's (its samples and speeds bitwise equal), only
// not all of it is kept at once.
#include <cstddef>
#include <deque>
#include <memory>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "planning/lookahead_profile.hpp"
#include "planning/motion_plan.hpp"
#include "planning/move_source.hpp"

namespace pkm::planning {

class PlanProducer {
 public:
  /// Plans `program` into `plan`, which it fills from its start (and keeps pointing at). Errors name the
  /// program line (bad options, a move no machine can make).
  static Result<std::unique_ptr<PlanProducer>> start(const Machine& machine,
                                                     const program::CanonicalProgram& program,
                                                     const PlanOptions& options, MotionPlan& plan);
  /// The same with the moves from `moves` (a reader still reading): `program` gives the file's name and
  /// where the program starts, its own moves unused.
  static Result<std::unique_ptr<PlanProducer>> start(const Machine& machine,
                                                     const program::CanonicalProgram& program,
                                                     std::unique_ptr<MoveSource> moves,
                                                     const PlanOptions& options, MotionPlan& plan);
  ~PlanProducer();

  /// Plans on until the timed samples reach past `time_s`, or the program ends.
  Status extend_to(double time_s);
  /// Plans the rest of the program. Then the plan's duration, statistics and the ticks' bound are final.
  /// Unless `keep_whole`, the plan is released as it is made (for its duration and statistics alone).
  Status run_to_end(bool keep_whole);
  bool finished() const { return finished_; }
  /// Forgets the samples before `sample` and the path before segment `segment` (indices along the whole
  /// plan), keeping what the planning itself still needs.
  void release(std::size_t sample, int segment);
  /// The lines of the program file (for the progress through it).
  int line_count() const { return moves_->line_count(); }
  /// The wall time spent planning (and waiting for the reader's moves) so far.
  double planning_s() const { return planning_s_; }
  /// The most samples and segments the plan held at once.
  std::size_t peak_samples() const { return peak_samples_; }
  std::size_t peak_segments() const { return peak_segments_; }

 private:
  struct Stages;
  PlanProducer(const Machine& machine, const program::CanonicalProgram& program,
               std::unique_ptr<MoveSource> moves, const PlanOptions& options, MotionPlan& plan);
  Status pump();
  Status pump_one_move();
  Error refuse(const Error& first) const;
  void take_planned();
  void append_sample(const PlannedSample& sample, int segment);
  Error too_many_ticks() const;
  Status finish_plan();

  const Machine& machine_;
  const program::CanonicalProgram& program_;
  std::unique_ptr<MoveSource> moves_;
  PlanOptions options_;
  MotionPlan& plan_;
  std::unique_ptr<Stages> stages_;
  int next_move_ = 0;  ///< moves read so far
  bool finished_ = false;
  std::deque<int> waiting_segment_;  ///< the segments of the samples in the look-ahead window, in order
  double clock_s_ = 0.0;             ///< the unfiltered profile's departure from the sample appended last
  double tick_bound_s_ = 0.0;        ///< the time at which the ticks pass PlanOptions::max_ticks
  int crossing_line_ = 0;            ///< the line of the first sample after the bound (0: none yet)
  int last_line_ = 0;                ///< the line of the sample appended last
  double slowest_s_ = 0.0;           ///< the longest time between two samples, and its line
  int slowest_line_ = 0;
  std::size_t peak_samples_ = 0, peak_segments_ = 0;
  bool measuring_length_ = false;  ///< planning on past the bound on the ticks, for the refusal's figures
  double planning_s_ = 0.0;
};

/// A plan to stream with memory bounded by the look-ahead window: the window `source` extends while the ticks
/// stream (StreamOptions::source). Its duration and statistics are known once the source has finished; a
/// refusal (the bound on the ticks, the workspace) ends the stream, and the caller discards what it wrote.
/// Held by pointer: the source plans into `plan`.
struct StreamedPlan {
  MotionPlan plan;
  std::unique_ptr<PlanProducer> source;
};
Result<std::unique_ptr<StreamedPlan>> start_streamed_plan(const Machine& machine,
                                                          const program::CanonicalProgram& program,
                                                          const PlanOptions& options);
/// The same with the moves from `moves` (a reader of the program file).
Result<std::unique_ptr<StreamedPlan>> start_streamed_plan(const Machine& machine,
                                                          const program::CanonicalProgram& program,
                                                          const MoveSourceFactory& moves,
                                                          const PlanOptions& options);

}  // namespace pkm::planning
