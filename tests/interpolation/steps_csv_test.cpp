// steps.csv: its header and rows as the interpolator's consumers read them, exact numbers, and no file
// unless the writer finishes.
#include "interpolation/drive_output/steps_csv.hpp"

#include <gtest/gtest.h>

#include <string>

#include "interpolation/step_test_support.hpp"

namespace pkm::interpolation {
namespace {

TEST(StepsCsv, HeaderAndRowsAreIntegersAndExactTimes) {
  const test::StepTempDir dir;
  StepStreamHeader header = test::step_header(3);
  header.start_position = {100, -5, 0};
  StepsCsvWriter writer;
  ASSERT_TRUE(writer.open(steps_csv_path(dir.path().string()), header));
  StepPeriod first{0, 0.001, 12, {3, -1, 0}, {103, -6, 0}};
  StepPeriod second{1, 0.002, 13, {-2147483647 - 1, 2147483647, 64}, {103 - 2147483648L, 2147483641L, 64}};
  ASSERT_TRUE(writer.write(first));
  ASSERT_TRUE(writer.write(second));
  ASSERT_TRUE(writer.finish());
  EXPECT_EQ(test::read_bytes(dir.file("steps.csv")),
            "period,time_s,line,steps_1,steps_2,steps_3,position_1,position_2,position_3\n"
            "0,0.001,12,3,-1,0,103,-6,0\n"
            "1,0.002,13,-2147483648,2147483647,64,-2147483545,2147483641,64\n");
}

TEST(StepsCsv, RandomPeriodsReadBackExactly) {
  const test::StepTempDir dir;
  for (int actuators : {1, 3, 6}) {
    // An awkward period, so that the times need all their digits.
    const StepStreamHeader header = test::step_header(actuators, 1.0 / 3000.0);
    const auto periods = test::random_periods(header, 5000, 21U + static_cast<unsigned>(actuators));
    StepsCsvWriter writer;
    ASSERT_TRUE(writer.open(dir.file("steps.csv"), header));
    for (const StepPeriod& p : periods) ASSERT_TRUE(writer.write(p));
    ASSERT_TRUE(writer.finish());
    auto table = read_steps_csv(dir.file("steps.csv"));
    ASSERT_TRUE(table) << table.error().message;
    EXPECT_EQ(table->actuators, actuators);
    test::expect_same_periods(table->periods, periods, actuators);
  }
}

TEST(StepsCsv, AnAbandonedWriterLeavesNoFile) {
  const test::StepTempDir dir;
  const StepStreamHeader header = test::step_header(6);
  {
    StepsCsvWriter writer;
    ASSERT_TRUE(writer.open(dir.file("steps.csv"), header));
    for (const StepPeriod& p : test::random_periods(header, 50'000, 4U)) ASSERT_TRUE(writer.write(p));
  }
  EXPECT_EQ(dir.entries(), 0);
}

TEST(StepsCsv, ReadingErrorsNameTheFileAndLine) {
  const test::StepTempDir dir;
  const std::string path = dir.file("steps.csv");
  test::write_bytes(path, "period,time_s,line,steps_1,position_1\n0,0.001,1,2,2\n1,0.002,1,x,2\n");
  auto table = read_steps_csv(path);
  ASSERT_FALSE(table);
  EXPECT_NE(table.error().message.find(path + ":3:"), std::string::npos) << table.error().message;
  test::write_bytes(path, "time_s,q1_mm\n0,1\n");
  table = read_steps_csv(path);
  ASSERT_FALSE(table);
  EXPECT_NE(table.error().message.find(path + ":1:"), std::string::npos) << table.error().message;
  EXPECT_FALSE(read_steps_csv(dir.file("none.csv")));
}

TEST(StepsCsv, RowFormattingAtTheWidestNumbersFitsItsBuffer) {
  StepPeriod widest;
  widest.index = std::numeric_limits<long>::min();
  widest.time_s = -1.2345678901234567e-300;
  widest.line = std::numeric_limits<int>::min();
  widest.steps.fill(std::numeric_limits<std::int32_t>::min());
  widest.position.fill(std::numeric_limits<std::int64_t>::min());
  StepRowBuffer buffer;
  const std::string_view row = format_step_row(widest, kMaxActuators, buffer);
  EXPECT_LT(row.size(), buffer.size());
  EXPECT_EQ(row.back(), '\n');
}

}  // namespace
}  // namespace pkm::interpolation
