// The executor of planned motion (execution/step_executor.hpp) on generated nominal motions: random
// rest-to-rest moves of every drive inside the nominal share of the limits (execution_headroom.hpp), played
// with random feed holds, overrides, aborts, starved streams and software stops. What must hold at every
// period: the continuous set point within the drives' speed, acceleration and jerk limits, the whole steps
// within half a step of it, the planned steps themselves wherever K = 1, and the program's end reached.
#include "execution/step_executor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "execution/execution_headroom.hpp"

namespace pkm::execution {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPeriodS = 0.001;
constexpr int kDrives = 6;

// Limits in steps (1 µm steps): 100 mm/s, 2000 mm/s², 100 000 mm/s³.
const DriveLimits kLimits{1e5, 2e6, 1e8};

// A nominal motion sampled at the servo period: each drive makes rest-to-rest moves
// q = A·(u − sin(2πu)/(2π)), u = t/T, whose speed, acceleration and jerk peaks are 2A/T, 2πA/T², 4π²A/T³.
std::vector<NominalPeriod> random_motion(std::mt19937& rng, const DriveLimits& nominal, int periods) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<double>> values(kDrives,
                                          std::vector<double>(static_cast<std::size_t>(periods) + 1));
  for (int j = 0; j < kDrives; ++j) {
    double start = 500000.0 + 1000.0 * j;
    auto& q = values[static_cast<std::size_t>(j)];
    int k = 0;
    for (;;) {
      const double duration_s = 0.03 + 0.3 * unit(rng);
      const int length = static_cast<int>(duration_s / kPeriodS);
      if (k + length > periods - 50) break;  // the motion ends at rest, 50 periods or more before the end
      const double amplitude =
          std::min({nominal.speed * duration_s / 2.0, nominal.accel * duration_s * duration_s / (2.0 * kPi),
                    *nominal.jerk * std::pow(duration_s, 3) / (4.0 * kPi * kPi)}) *
          (2.0 * unit(rng) - 1.0);
      for (int i = 0; i < length; ++i, ++k) {
        const double u = static_cast<double>(i) / length;
        q[static_cast<std::size_t>(k)] = start + amplitude * (u - std::sin(2.0 * kPi * u) / (2.0 * kPi));
      }
      start += amplitude;
    }
    for (; k <= periods; ++k) q[static_cast<std::size_t>(k)] = start;
  }
  std::vector<NominalPeriod> motion(static_cast<std::size_t>(periods) + 1);
  for (int k = 0; k <= periods; ++k) {
    NominalPeriod& p = motion[static_cast<std::size_t>(k)];
    for (int j = 0; j < kDrives; ++j) {
      p.ideal_steps[j] = values[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
      p.position_steps[j] = std::llround(p.ideal_steps[j]);
    }
    p.line = 10 + k / 100;
  }
  return motion;
}

ExecutorSettings settings_for(const ExecutionHeadroom& headroom) {
  ExecutorSettings s;
  s.drives = kDrives;
  s.period_s = kPeriodS;
  s.max_override = headroom.max_override;
  s.rates = headroom.rates;
  s.min_position_steps.fill(0);
  s.max_position_steps.fill(2'000'000);
  return s;
}

// The executed set points, checked as they come: speed, acceleration and jerk by differences over the
// servo period against the drives' limits (a part in 10⁶ for rounding), whole steps within half a step.
struct LimitWatch {
  std::vector<ValueArray> last;
  double worst_speed = 0.0, worst_accel = 0.0, worst_jerk = 0.0;
  void add(const ExecutedPeriod& out) {
    for (int j = 0; j < kDrives; ++j)
      ASSERT_LE(std::abs(static_cast<double>(out.position_steps[j]) - out.set_point_steps[j]), 0.5 + 1e-9);
    last.push_back(out.set_point_steps);
    if (last.size() > 4) last.erase(last.begin());
    const std::size_t n = last.size();
    const double h = kPeriodS;
    for (int j = 0; j < kDrives; ++j) {
      if (n >= 2) worst_speed = std::max(worst_speed, std::abs(last[n - 1][j] - last[n - 2][j]) / h);
      if (n >= 3) {
        const double acc = std::abs(last[n - 1][j] - 2 * last[n - 2][j] + last[n - 3][j]) / (h * h);
        worst_accel = std::max(worst_accel, acc);
      }
      if (n >= 4)
        worst_jerk = std::max(
            worst_jerk, std::abs(last[n - 1][j] - 3 * last[n - 2][j] + 3 * last[n - 3][j] - last[n - 4][j]) /
                            (h * h * h));
    }
  }
  void expect_within(const DriveLimits& limits) const {
    EXPECT_LE(worst_speed, limits.speed * (1 + 1e-6));
    EXPECT_LE(worst_accel, limits.accel * (1 + 1e-6));
    EXPECT_LE(worst_jerk, *limits.jerk * (1 + 1e-6));
  }
};

// Feeds the executor up to `per_period` nominal periods per servo period (or none in a dry spell).
struct Feeder {
  const std::vector<NominalPeriod>& motion;
  std::size_t next = 1;  // motion[0] is the start position
  void feed(StepExecutor& executor, int per_period) {
    for (int i = 0; i < per_period && next < motion.size() && executor.has_room(); ++i)
      executor.push(motion[next++]);
    if (next == motion.size()) executor.end_of_program();
  }
};

// The headroom every test plans within: overrides up to 120 %, half the acceleration for the motion.
ExecutionHeadroom test_headroom() {
  auto headroom = execution_headroom(kLimits, 1.2, 0.5, kPeriodS);
  EXPECT_TRUE(headroom) << headroom.error().message;
  return *headroom;
}

// One execution of a nominal motion: the executor started at its first point, its feeder, what watches it.
struct Execution {
  Execution(std::vector<NominalPeriod> nominal, const ExecutorSettings& settings)
      : motion(std::move(nominal)), executor(std::make_unique<StepExecutor>(settings)), feeder{motion} {
    executor->start(motion[0].position_steps);
  }
  std::vector<NominalPeriod> motion;
  std::unique_ptr<StepExecutor> executor;
  Feeder feeder;
  LimitWatch watch;
  ExecutedPeriod out;
};

TEST(StepExecutor, ReleasesThePlannedStepsThemselvesAtFullFeed) {
  std::mt19937 rng(11);
  const ExecutionHeadroom headroom = test_headroom();
  for (int trial = 0; trial < 5; ++trial) {
    Execution run(random_motion(rng, headroom.nominal, 3000), settings_for(headroom));
    run.feeder.feed(*run.executor, StepExecutor::kWindow);  // a full window first, then one per period
    StepArray before = run.motion[0].position_steps;
    for (std::size_t k = 1; k < run.motion.size(); ++k) {
      run.executor->period({}, run.out);
      run.feeder.feed(*run.executor, 1);
      ASSERT_EQ(run.out.position_steps, run.motion[k].position_steps) << "period " << k;
      for (int j = 0; j < kDrives; ++j)
        ASSERT_EQ(run.out.steps[j], run.motion[k].position_steps[j] - before[j]);
      before = run.out.position_steps;
      EXPECT_EQ(run.out.line, run.motion[k].line);
    }
    EXPECT_EQ(run.out.state, ExecutionState::finished);
  }
}

// An abort before the program has begun (the stream not yet far enough ahead) drops it without a step.
TEST(StepExecutor, AnAbortBeforeTheStartDropsTheProgramWithoutMoving) {
  std::mt19937 rng(19);
  const ExecutionHeadroom headroom = test_headroom();
  Execution run(random_motion(rng, headroom.nominal, 3000), settings_for(headroom));
  run.feeder.feed(*run.executor, 5);
  run.executor->period({1.0, false, true}, run.out);
  EXPECT_EQ(run.out.state, ExecutionState::aborted);
  EXPECT_EQ(run.out.position_steps, run.motion[0].position_steps);
  EXPECT_FALSE(run.executor->has_room());
  run.executor->period({}, run.out);
  EXPECT_EQ(run.out.position_steps, run.motion[0].position_steps);
}

// A stream that comes in slowly at first: the drives wait at the start until it is far enough ahead, then
// the program runs as planned, every period's steps the planned ones.
TEST(StepExecutor, WaitsAtTheStartForTheStreamAndThenReleasesThePlannedSteps) {
  std::mt19937 rng(18);
  const ExecutionHeadroom headroom = test_headroom();
  Execution run(random_motion(rng, headroom.nominal, 3000), settings_for(headroom));
  std::size_t next = 1;
  long waited = 0;
  for (long period = 0; period < 20000 && run.executor->state() != ExecutionState::finished; ++period) {
    run.feeder.feed(*run.executor, period % 3 == 0 ? 2 : 1);  // 1.33 nominal periods per servo period
    run.executor->period({}, run.out);
    if (run.out.tau_periods == 0.0) {
      ++waited;
      ASSERT_EQ(run.out.position_steps, run.motion[0].position_steps);
      continue;
    }
    ASSERT_LT(next, run.motion.size());
    ASSERT_EQ(run.out.tau_periods, static_cast<double>(next));
    ASSERT_EQ(run.out.position_steps, run.motion[next].position_steps) << "period " << next;
    ++next;
  }
  EXPECT_GT(waited, 10);
  EXPECT_EQ(next, run.motion.size());
  EXPECT_EQ(run.executor->state(), ExecutionState::finished);
}

TEST(StepExecutor, HoldsAndOverridesAtRandomPeriodsWithinTheLimitsAndEndWhereThePlanEnds) {
  std::mt19937 rng(12);
  const ExecutionHeadroom headroom = test_headroom();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Execution run(random_motion(rng, headroom.nominal, 4000), settings_for(headroom));
    ExecutionControls controls;
    long period = 0;
    for (; period < 200000 && run.executor->state() != ExecutionState::finished; ++period) {
      if (unit(rng) < 0.004) controls.hold = !controls.hold;
      if (unit(rng) < 0.003) controls.override_factor = std::array{0.3, 1.0, 1.2, 0.0, 0.75}[rng() % 5];
      if (period > 150000) controls = {};  // let it end
      run.feeder.feed(*run.executor, 2);
      run.executor->period(controls, run.out);
      run.watch.add(run.out);
      if (testing::Test::HasFatalFailure()) return;
      ASSERT_NE(run.out.state, ExecutionState::stopped_at_limit);
    }
    ASSERT_EQ(run.executor->state(), ExecutionState::finished) << "trial " << trial;
    EXPECT_EQ(run.out.position_steps, run.motion.back().position_steps);
    run.watch.expect_within(kLimits);
  }
}

TEST(StepExecutor, OverrideStepsKeepTheLimitsAndThePath) {
  std::mt19937 rng(13);
  const ExecutionHeadroom headroom = test_headroom();
  Execution run(random_motion(rng, headroom.nominal, 6000), settings_for(headroom));
  double furthest_tau = 0.0;
  for (long period = 0; period < 50000 && run.executor->state() != ExecutionState::finished; ++period) {
    const double k = period < 1500 ? 1.0 : period < 3500 ? 0.3 : 1.2;  // 100 → 30 → 120 %
    run.feeder.feed(*run.executor, 2);
    run.executor->period({k, false, false}, run.out);
    run.watch.add(run.out);
    // The path: the set point is the nominal motion at τ (τ only moves forward).
    ASSERT_GE(run.out.tau_periods, furthest_tau);
    furthest_tau = run.out.tau_periods;
    const auto lower = static_cast<std::size_t>(std::floor(run.out.tau_periods));
    const std::size_t upper = std::min(lower + 1, run.motion.size() - 1);
    for (int j = 0; j < kDrives; ++j) {
      const double a = run.motion[lower].ideal_steps[j], b = run.motion[upper].ideal_steps[j];
      ASSERT_GE(run.out.set_point_steps[j], std::min(a, b) - 1.0);
      ASSERT_LE(run.out.set_point_steps[j], std::max(a, b) + 1.0);
    }
  }
  EXPECT_EQ(run.executor->state(), ExecutionState::finished);
  EXPECT_EQ(run.out.position_steps, run.motion.back().position_steps);
  run.watch.expect_within(kLimits);
}

TEST(StepExecutor, AbortStopsWithinTheLimitsAndDropsTheRest) {
  std::mt19937 rng(14);
  const ExecutionHeadroom headroom = test_headroom();
  for (int trial = 0; trial < 10; ++trial) {
    Execution run(random_motion(rng, headroom.nominal, 4000), settings_for(headroom));
    const long abort_at = 100 + static_cast<long>(rng() % 3000);
    long period = 0;
    run.feeder.feed(*run.executor, StepExecutor::kWindow);
    for (; period < 20000 && run.executor->state() == ExecutionState::running; ++period) {
      run.feeder.feed(*run.executor, 1);
      run.executor->period({1.0, false, period >= abort_at}, run.out);
      run.watch.add(run.out);
    }
    ASSERT_EQ(run.executor->state(), ExecutionState::aborted) << "trial " << trial;
    EXPECT_LT(run.out.tau_periods, static_cast<double>(run.motion.size() - 1));
    const StepArray stopped = run.out.position_steps;
    for (int i = 0; i < 10; ++i) {
      run.executor->period({}, run.out);
      EXPECT_EQ(run.out.position_steps, stopped);  // it stays where it stopped
    }
    run.watch.expect_within(kLimits);
  }
}

TEST(StepExecutor, AStreamThatRunsDrySlowsWithinTheLimitsAndCatchesUp) {
  std::mt19937 rng(15);
  const ExecutionHeadroom headroom = test_headroom();
  Execution run(random_motion(rng, headroom.nominal, 8000), settings_for(headroom));
  bool starved = false;
  for (long period = 0; period < 100000 && run.executor->state() != ExecutionState::finished; ++period) {
    // Bursts with dry spells: on average slower than the motion for a while, then fast again.
    const int burst = period % 400 < 300 ? 0 : period < 20000 ? 3 : 8;
    run.feeder.feed(*run.executor, burst);
    run.executor->period({}, run.out);
    starved = starved || run.out.state == ExecutionState::starved;
    run.watch.add(run.out);
  }
  EXPECT_TRUE(starved);
  EXPECT_EQ(run.executor->state(), ExecutionState::finished);
  EXPECT_EQ(run.out.position_steps, run.motion.back().position_steps);
  run.watch.expect_within(kLimits);
}

TEST(StepExecutor, NeverReleasesAPositionOutsideTheSoftwareStops) {
  std::mt19937 rng(16);
  const ExecutionHeadroom headroom = test_headroom();
  for (int trial = 0; trial < 10; ++trial) {
    auto motion = random_motion(rng, headroom.nominal, 4000);
    // A stop inside the motion's range of drive 3: the stream reaches past it somewhere.
    ExecutorSettings settings = settings_for(headroom);
    std::int64_t highest = 0;
    for (const auto& p : motion) highest = std::max(highest, p.position_steps[2]);
    const std::int64_t lowest = motion[0].position_steps[2];
    if (highest - lowest < 200) continue;
    settings.max_position_steps[2] = lowest + (highest - lowest) / 2;
    Execution run(std::move(motion), settings);
    run.feeder.feed(*run.executor, StepExecutor::kWindow);
    for (long period = 0; period < 20000 && run.executor->state() == ExecutionState::running; ++period) {
      run.feeder.feed(*run.executor, 1);
      run.executor->period({}, run.out);
      ASSERT_LE(run.out.position_steps[2], settings.max_position_steps[2]);
      run.watch.add(run.out);
    }
    EXPECT_EQ(run.executor->state(), ExecutionState::stopped_at_limit);
    EXPECT_GE(run.executor->fault_line(), 10);
    run.watch.expect_within(kLimits);
  }
}

// The sharp case of the headroom: a drive cruising at the nominal speed limit when the hold comes. Its
// acceleration is then q'·K̇ alone, and the hold uses exactly the share (1 − η) of the limit that it has.
TEST(StepExecutor, AHoldAtFullSpeedUsesItsShareOfTheAccelerationAndNoMore) {
  const ExecutionHeadroom headroom = test_headroom();
  std::vector<NominalPeriod> motion(3001);
  for (std::size_t k = 0; k < motion.size(); ++k) {
    for (int j = 0; j < kDrives; ++j) {
      motion[k].ideal_steps[j] = 500000.0 + (j % 2 ? 1.0 : -1.0) * headroom.nominal.speed * kPeriodS * k;
      motion[k].position_steps[j] = std::llround(motion[k].ideal_steps[j]);
    }
  }
  Execution run(std::move(motion), settings_for(headroom));
  run.feeder.feed(*run.executor, StepExecutor::kWindow);
  for (long period = 0; period < 1200; ++period) {
    run.feeder.feed(*run.executor, 1);
    run.executor->period({1.0, period >= 500, false}, run.out);
    if (period > 2) run.watch.add(run.out);  // past the start, where the cruise begins at full speed
  }
  EXPECT_EQ(run.out.factor, 0.0);
  const double share = (1.0 - headroom.motion_share) * kLimits.accel;
  EXPECT_LE(run.watch.worst_accel, share * (1 + 1e-6));
  EXPECT_GE(run.watch.worst_accel, 0.95 * share);
  run.watch.expect_within(kLimits);
}

TEST(OverrideLaw, ReachesEveryTargetExactlyWithoutOvershootWithinItsRates) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const OverrideRates rates{12.0, 600.0};
  OverrideLaw law(rates, kPeriodS);
  for (int change = 0; change < 200; ++change) {
    const double target = 1.2 * unit(rng);
    const double from = law.factor();
    int periods = 0;
    double previous_rate = law.rate_per_s();
    while (!law.settled_at(target) && periods < 100000) {
      law.advance(target);
      ++periods;
      EXPECT_LE(std::abs(law.rate_per_s()), rates.max_rate_per_s * (1 + 1e-12));
      EXPECT_LE(std::abs(law.rate_per_s() - previous_rate), rates.max_accel_per_s2 * kPeriodS * (1 + 1e-9));
      previous_rate = law.rate_per_s();
      // Between where it came from and the target, never beyond.
      EXPECT_GE(law.factor(), std::min(from, target) - 1e-15);
      EXPECT_LE(law.factor(), std::max(from, target) + 1e-15);
    }
    ASSERT_TRUE(law.settled_at(target)) << "from " << from << " to " << target;
    // No slower than twice the time of a rate-limited ramp plus the rate's own rise and fall.
    const double ramp_s =
        std::abs(target - from) / rates.max_rate_per_s + 2.0 * rates.max_rate_per_s / rates.max_accel_per_s2;
    EXPECT_LE(periods * kPeriodS, 2.0 * ramp_s + 0.01);
  }
}

TEST(ExecutionHeadroom, SharesTheLimitsAndRefusesWhatCannotWork) {
  auto h = execution_headroom(kLimits, 1.2, 0.5, kPeriodS);
  ASSERT_TRUE(h);
  EXPECT_DOUBLE_EQ(h->nominal.speed * 1.2, kLimits.speed);
  EXPECT_DOUBLE_EQ(h->nominal.accel * 1.44 / 0.5, kLimits.accel);
  // The executed acceleration bound with K at its largest and changing at its fastest is the limit.
  EXPECT_NEAR(h->nominal.accel * 1.44 + h->nominal.speed * h->rates.max_rate_per_s, kLimits.accel, 1e-6);
  // A jerk limit too low for any override change, and no limits at all, are refused with a reason.
  auto low = execution_headroom({1e5, 2e6, 1e5}, 1.2, 0.5, kPeriodS);
  ASSERT_FALSE(low);
  EXPECT_NE(low.error().message.find("jerk"), std::string::npos);
  EXPECT_FALSE(execution_headroom({0.0, 2e6, std::nullopt}, 1.2, 0.5, kPeriodS));
  EXPECT_FALSE(execution_headroom(kLimits, 0.9, 0.5, kPeriodS));
  // Without a jerk limit K̈ takes K̇'s largest value in kRateRiseS.
  auto no_jerk = execution_headroom({1e5, 2e6, std::nullopt}, 1.2, 0.5, kPeriodS);
  ASSERT_TRUE(no_jerk);
  EXPECT_DOUBLE_EQ(no_jerk->rates.max_accel_per_s2 * kRateRiseS, no_jerk->rates.max_rate_per_s);
}

}  // namespace
}  // namespace pkm::execution
