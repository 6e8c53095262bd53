// The contract of the tick observers (planning/tick_observer.hpp) as stream_plan keeps it: on_start once with
// the number of ticks that follow, every tick in order to every observer, on_finish once after the last; an
// observer's error stops the run at that tick, and later observers and ticks see nothing more.
#include "planning/tick_observer.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "plan_test_support.hpp"
#include "planning/plan_stream.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

class CountingObserver final : public planning::TickObserver {
 public:
  explicit CountingObserver(long fail_at = -1) : fail_at_(fail_at) {}
  Status on_start(long tick_count) override {
    ++starts;
    announced = tick_count;
    return ok_status();
  }
  Status on_tick(const planning::ServoTick& tick, const planning::RunMonitor&) override {
    EXPECT_EQ(starts, 1) << "a tick before on_start";
    EXPECT_EQ(finishes, 0) << "a tick after on_finish";
    EXPECT_EQ(tick.index, ticks) << "ticks out of order";
    if (ticks == fail_at_) return Error{ErrorCode::bad_input, "the listener gave up"};
    ++ticks;
    return ok_status();
  }
  Status on_finish() override {
    ++finishes;
    return ok_status();
  }
  long announced = -1, ticks = 0;
  int starts = 0, finishes = 0;

 private:
  long fail_at_;
};

// A random zigzag of straight moves in the machine's x y (or y z) plane around its start.
std::string random_zigzag(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> offset(-2.0, 2.0);
  std::string text = "G21 G90 G64 P0.01\nF1200\n";
  for (int k = 0; k < 8; ++k)
    text += "G1 X" + std::to_string(offset(rng)) + " Y" + std::to_string(offset(rng)) + "\n";
  return text + "M2\n";
}

TEST(TickObserver, StartsWithTheTickCountSeesEveryTickInOrderAndFinishesOnce) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  std::mt19937_64 rng(20261206);
  for (int trial = 0; trial < 4; ++trial) {
    const auto program = test::gcode_for(machine, random_zigzag(rng));
    const planning::MotionPlan plan = test::plan_or_fail(machine, program);
    CountingObserver first, second;
    planning::TickObserver* observers[] = {&first, &second};
    auto streamed = planning::stream_plan(plan, machine, {}, observers);
    ASSERT_TRUE(streamed.ok()) << streamed.error().message;
    for (const CountingObserver* o : {&first, &second}) {
      EXPECT_EQ(o->starts, 1);
      EXPECT_EQ(o->finishes, 1);
      EXPECT_GT(o->ticks, 1);
      EXPECT_EQ(o->announced, o->ticks) << "on_start announced another count than streamed";
    }
  }
}

TEST(TickObserver, AnErrorStopsTheRunAtThatTick) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  std::mt19937_64 rng(7);
  const planning::MotionPlan plan = test::plan_or_fail(machine, test::gcode_for(machine, random_zigzag(rng)));
  CountingObserver probe;
  planning::TickObserver* alone[] = {&probe};
  ASSERT_TRUE(planning::stream_plan(plan, machine, {}, alone).ok());
  const long stop_at = std::uniform_int_distribution<long>(0, probe.ticks - 1)(rng);

  CountingObserver failing(stop_at), after;
  planning::TickObserver* observers[] = {&failing, &after};
  auto streamed = planning::stream_plan(plan, machine, {}, observers);
  ASSERT_FALSE(streamed.ok());
  EXPECT_EQ(streamed.error().message, "the listener gave up");
  EXPECT_EQ(failing.ticks, stop_at);
  EXPECT_EQ(after.ticks, stop_at) << "the observer after the failing one saw the failed tick";
  EXPECT_EQ(failing.finishes + after.finishes, 0);
}

}  // namespace
}  // namespace pkm
