#pragma once
// Helpers for the drive-step output tests: seeded random step sequences with consistent position codes,
// fresh temporary directories, whole files as bytes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "interpolation/quantisation/step_period.hpp"

namespace pkm::test {

/// A header for `actuators` drives at `period_s`, with start positions far from zero on both sides.
inline interpolation::StepStreamHeader step_header(int actuators, double period_s = 0.001) {
  interpolation::StepStreamHeader header;
  header.actuators = actuators;
  header.period_s = period_s;
  header.step_mm = 0.001;
  for (int j = 0; j < actuators; ++j) header.start_position[j] = (j % 2 ? -1 : 1) * (700'000 + 1'000 * j);
  header.machine = "examples/machines/hexapod_ch5.yaml";
  return header;
}

/// `count` periods after `header`: mostly small steps with reversals, some zeros, now and then a large count
/// (beyond 2^20, up to the int32 extremes); program lines that go up, stay and sometimes go back.
inline std::vector<interpolation::StepPeriod> random_periods(const interpolation::StepStreamHeader& header,
                                                             long count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> kind(0, 99), small(-63, 63), medium(-5000, 5000), line_step(-2, 5);
  std::uniform_int_distribution<std::int32_t> large(1 << 20, std::numeric_limits<std::int32_t>::max());
  std::vector<interpolation::StepPeriod> periods;
  auto position = header.start_position;
  int line = 1;
  for (long k = 0; k < count; ++k) {
    interpolation::StepPeriod p;
    p.index = k;
    p.time_s = static_cast<double>(k + 1) * header.period_s;
    if (kind(random) < 10) line = std::max(0, line + line_step(random));
    p.line = line;
    for (int j = 0; j < header.actuators; ++j) {
      const int which = kind(random);
      std::int32_t steps = 0;
      if (which < 10)
        steps = 0;
      else if (which < 80)
        steps = small(random);
      else if (which < 95)
        steps = medium(random);
      else if (which < 98)
        steps = (kind(random) % 2 ? -1 : 1) * large(random);
      else
        steps =
            which == 98 ? std::numeric_limits<std::int32_t>::min() : std::numeric_limits<std::int32_t>::max();
      p.steps[j] = steps;
      position[j] += steps;
      p.position[j] = position[j];
    }
    periods.push_back(p);
  }
  return periods;
}

inline void expect_same_periods(const std::vector<interpolation::StepPeriod>& actual,
                                const std::vector<interpolation::StepPeriod>& expected, int actuators) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t k = 0; k < actual.size(); ++k) {
    SCOPED_TRACE("period " + std::to_string(k));
    EXPECT_EQ(actual[k].index, expected[k].index);
    EXPECT_EQ(actual[k].time_s, expected[k].time_s);
    EXPECT_EQ(actual[k].line, expected[k].line);
    for (int j = 0; j < actuators; ++j) {
      EXPECT_EQ(actual[k].steps[j], expected[k].steps[j]) << "actuator " << j + 1;
      EXPECT_EQ(actual[k].position[j], expected[k].position[j]) << "actuator " << j + 1;
    }
    if (::testing::Test::HasFailure()) return;
  }
}

/// A fresh empty directory named after the running test (and this process), removed by the destructor.
class StepTempDir {
 public:
  StepTempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("pkm_steps_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~StepTempDir() { std::filesystem::remove_all(path_); }
  StepTempDir(const StepTempDir&) = delete;
  StepTempDir& operator=(const StepTempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  int entries() const {
    return static_cast<int>(
        std::distance(std::filesystem::directory_iterator(path_), std::filesystem::directory_iterator{}));
  }

 private:
  std::filesystem::path path_;
};

inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace pkm::test
