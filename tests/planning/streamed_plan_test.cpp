// The plan made through its look-ahead window while the ticks stream (plan_producer.hpp) against the whole
// plan of the same program: every tick equal to the bit, what the monitor measured equal, and the window's
// memory not growing with the program.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "cam_program_generator.hpp"
#include "plan_test_support.hpp"
#include "planning/plan_producer.hpp"
#include "planning/plan_stream.hpp"
#include "test_support.hpp"

namespace pkm::planning {
namespace {

using test::CamShape;

class TickRecorder final : public TickObserver {
 public:
  Status on_start(long tick_count) override {
    announced = tick_count;
    return ok_status();
  }
  Status on_tick(const ServoTick& tick, const RunMonitor& monitor) override {
    ticks.push_back(tick);
    path_error_mm.push_back(monitor.last_path_error_mm());
    return ok_status();
  }
  long announced = 0;
  std::vector<ServoTick> ticks;
  std::vector<double> path_error_mm;
};

struct Streamed {
  TickRecorder recorder;
  RunSummary summary;
  std::size_t peak_samples = 0, peak_segments = 0;
  PlanStatistics statistics;
};

Streamed stream_through_window(const Machine& machine, const program::CanonicalProgram& program) {
  Streamed out;
  auto started = start_streamed_plan(machine, program, {});
  if (!started) throw std::runtime_error(started.error().message);
  StreamOptions options;
  options.source = (*started)->source.get();
  TickObserver* observers[] = {&out.recorder};
  auto summary = stream_plan((*started)->plan, machine, options, observers);
  if (!summary) throw std::runtime_error(summary.error().message);
  out.summary = *summary;
  out.peak_samples = (*started)->source->peak_samples();
  out.peak_segments = (*started)->source->peak_segments();
  out.statistics = (*started)->plan.statistics;
  return out;
}

/// A CAM-like program of `points` short moves (and `repeats` times the same shape, when asked).
void expect_same_ticks(const Machine& machine, const program::CanonicalProgram& program,
                       const std::string& label) {
  const MotionPlan whole = test::plan_or_fail(machine, program);
  TickRecorder whole_ticks;
  TickObserver* observers[] = {&whole_ticks};
  auto whole_summary = stream_plan(whole, machine, {}, observers);
  ASSERT_TRUE(whole_summary.ok()) << label << whole_summary.error().message;
  const Streamed streamed = stream_through_window(machine, program);
  // The window was released behind the ticks: it never held the whole plan.
  EXPECT_LT(streamed.peak_samples, whole.samples.size()) << label;
  EXPECT_LT(streamed.peak_segments, whole.path.segments.size()) << label;
  EXPECT_EQ(streamed.statistics.samples, whole.statistics.samples) << label;
  EXPECT_EQ(streamed.statistics.segments, whole.statistics.segments) << label;
  // The streamed run cannot announce its ticks (its end is not planned yet); the whole plan's count is
  // what it streams.
  EXPECT_EQ(streamed.recorder.announced, 0) << label;
  EXPECT_EQ(static_cast<long>(streamed.recorder.ticks.size()), whole_ticks.announced) << label;
  ASSERT_EQ(streamed.recorder.ticks.size(), whole_ticks.ticks.size()) << label;
  for (std::size_t k = 0; k < whole_ticks.ticks.size(); ++k) {
    const ServoTick& a = whole_ticks.ticks[k];
    const ServoTick& b = streamed.recorder.ticks[k];
    ASSERT_EQ(a.s, b.s) << label << " tick " << k;
    ASSERT_EQ(a.segment, b.segment) << label << " tick " << k;
    ASSERT_EQ(a.line, b.line) << label << " tick " << k;
    ASSERT_TRUE(a.actuators == b.actuators) << label << " tick " << k;
    const double ea = whole_ticks.path_error_mm[k], eb = streamed.recorder.path_error_mm[k];
    ASSERT_TRUE(ea == eb || (std::isnan(ea) && std::isnan(eb))) << label << " tick " << k;
  }
  EXPECT_EQ(streamed.summary.max_actuator_speed, whole_summary->max_actuator_speed) << label;
  EXPECT_EQ(streamed.summary.max_path_error_mm, whole_summary->max_path_error_mm) << label;
  EXPECT_EQ(streamed.summary.max_path_jerk, whole_summary->max_path_jerk) << label;
}

TEST(StreamedPlan, EveryTickEqualsTheWholePlansOnGeneratedCamPrograms) {
  for (const char* file : {"hexapod_ch5.yaml", "tricept.yaml", "planar3.yaml"}) {
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    int n = 0;
    for (CamShape shape : {CamShape::noisy_circle, CamShape::zigzag, CamShape::mixed_arcs}) {
      const std::string text = test::cam_program(machine, shape, 2500, 7000 + n++);
      const program::CanonicalProgram program = test::gcode_for(machine, text, "cam.ngc");
      expect_same_ticks(machine, program, std::string(file) + " " + test::cam_shape_name(shape));
    }
  }
}

TEST(StreamedPlan, TheWindowDoesNotGrowWithTheProgram) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const std::string once = test::cam_program(machine, CamShape::noisy_circle, 2000, 77, 2);
  const std::string ten_times = test::cam_program(machine, CamShape::noisy_circle, 2000, 77, 20);
  const Streamed small = stream_through_window(machine, test::gcode_for(machine, once, "cam.ngc"));
  const Streamed large = stream_through_window(machine, test::gcode_for(machine, ten_times, "cam.ngc"));
  EXPECT_GT(large.statistics.samples, 9 * small.statistics.samples);
  EXPECT_LE(large.peak_samples, small.peak_samples * 11 / 10);
  EXPECT_LE(large.peak_segments, small.peak_segments * 11 / 10);
}

}  // namespace
}  // namespace pkm::planning
