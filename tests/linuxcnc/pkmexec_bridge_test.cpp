// The C bridge of LinuxCNC's pkmexec component (linuxcnc/pkmexec_bridge.h) between programs: while no program
// moves the drives the executor follows them wherever something else (LinuxCNC jogging or homing) puts them,
// to the nearest step, and a program must then start there; one that comes while the drives are not handed
// over is refused with its own state, and the executor stays where it was.
#include "pkmexec_bridge.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <random>

#include "test_support.hpp"

namespace pkm {
namespace {

struct ExecFree {
  void operator()(pkmexec_executor* e) const { pkmexec_free(e); }
};
using ExecHandle = std::unique_ptr<pkmexec_executor, ExecFree>;

ExecHandle load_ch5() {
  char error[1024] = {0};
  ExecHandle e(pkmexec_create(test::source_path("examples/machines/hexapod_ch5.yaml").c_str(), 1e-3, error,
                              sizeof error));
  EXPECT_TRUE(e) << error;
  return e;
}

// One period with the operator's controls at rest; the executor's output.
pkmexec_period_out one_period(pkmexec_executor* e) {
  pkmexec_period_out out{};
  pkmexec_period(e, 1.0, 0, 0, &out);
  return out;
}

TEST(PkmexecBridge, FollowsTheDrivesBetweenProgramsAndStartsOnlyWhereTheyAre) {
  ExecHandle e = load_ch5();
  ASSERT_TRUE(e);
  const int n = pkmexec_drive_count(e.get());
  const double step = pkmexec_step(e.get());
  std::array<long long, PKMEXEC_MAX_DRIVES> home{};
  pkmexec_home_steps(e.get(), home.data());
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> jog(-20.0, 20.0);
  for (int trial = 0; trial < 20; ++trial) {
    // LinuxCNC jogged the drives somewhere: the executor follows, whole steps, and its output says so.
    std::array<double, PKMEXEC_MAX_DRIVES> at{};
    std::array<long long, PKMEXEC_MAX_DRIVES> at_steps{};
    for (int j = 0; j < n; ++j) {
      at[j] = home[j] * step + jog(rng);
      at_steps[j] = std::llround(at[j] / step);
    }
    pkmexec_follow(e.get(), at.data());
    EXPECT_EQ(pkmexec_active(e.get()), 0);
    const pkmexec_period_out out = one_period(e.get());
    for (int j = 0; j < n; ++j) {
      EXPECT_EQ(out.position[j], at_steps[j]);
      EXPECT_EQ(out.set_point[j], static_cast<double>(at_steps[j]));
    }
    // A program from home is refused unless the drives are there; one from where they are starts.
    EXPECT_EQ(pkmexec_start(e.get(), home.data(), 1), -1);
    EXPECT_EQ(pkmexec_state(e.get()), PKMEXEC_REFUSED);
    EXPECT_EQ(pkmexec_active(e.get()), 0);
    // Not handed over: refused with its own state, however right the start.
    EXPECT_EQ(pkmexec_start(e.get(), at_steps.data(), 0), -1);
    EXPECT_EQ(pkmexec_state(e.get()), PKMEXEC_NOT_HANDED_OVER);
    EXPECT_EQ(pkmexec_has_room(e.get()), 0);
    ASSERT_EQ(pkmexec_start(e.get(), at_steps.data(), 1), 0);
    EXPECT_EQ(pkmexec_active(e.get()), 1);
    // A running program owns the drives: following does nothing until it has ended.
    std::array<double, PKMEXEC_MAX_DRIVES> elsewhere{};
    for (int j = 0; j < n; ++j) elsewhere[j] = at[j] + 5.0;
    pkmexec_follow(e.get(), elsewhere.data());
    pkmexec_end_of_program(e.get());  // an empty program: it ends where it started
    pkmexec_period_out last{};
    for (int k = 0; k < 10 && pkmexec_active(e.get()); ++k) last = one_period(e.get());
    EXPECT_EQ(pkmexec_active(e.get()), 0);
    EXPECT_EQ(last.state, PKMEXEC_FINISHED);
    for (int j = 0; j < n; ++j) EXPECT_EQ(last.position[j], at_steps[j]);
  }
}

}  // namespace
}  // namespace pkm
