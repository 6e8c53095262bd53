// The binary step stream (steps.bin): exact round trips, its size, agreement with steps.csv, and a reader
// that refuses truncated or damaged files by name and byte offset, and a writer that leaves nothing behind
// unless it finishes.
#include "interpolation/drive_output/step_stream.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "interpolation/drive_output/steps_csv.hpp"
#include "interpolation/step_test_support.hpp"

namespace pkm::interpolation {
namespace {

namespace fs = std::filesystem;

Status write_stream(const std::string& path, const StepStreamHeader& header,
                    const std::vector<StepPeriod>& periods) {
  StepStreamWriter writer;
  if (auto opened = writer.open(path, header); !opened) return opened;
  for (const StepPeriod& p : periods) {
    if (auto written = writer.write(p); !written) return written;
  }
  return writer.finish();
}

std::vector<StepPeriod> read_stream(StepStreamReader& reader) {
  std::vector<StepPeriod> periods;
  StepPeriod p;
  while (reader.next(p)) periods.push_back(p);
  EXPECT_FALSE(reader.error()) << reader.error()->message;
  return periods;
}

std::string step_stream_error_of(const std::string& path) {
  StepStreamReader reader;
  auto opened = reader.open(path);
  if (!opened) return opened.error().message;
  StepPeriod p;
  while (reader.next(p)) {
  }
  return reader.error() ? reader.error()->message : std::string("no error");
}

// Little-endian u64 at `offset` of `bytes`, replaced.
void put_u64(std::string& bytes, std::size_t offset, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) bytes[offset + i] = static_cast<char>((value >> (8 * i)) & 0xFFU);
}
void put_u32(std::string& bytes, std::size_t offset, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes[offset + i] = static_cast<char>((value >> (8 * i)) & 0xFFU);
}
// Recomputes the end record's checksum after an edit of the bytes before it.
void reseal(std::string& bytes) {
  const std::size_t end = bytes.size() - 24;
  put_u32(bytes, end + 16, step_stream_crc32(bytes.data(), end));
}

TEST(StepStream, RandomPeriodsRoundTripExactly) {
  const test::StepTempDir dir;
  for (int actuators : {1, 3, 6}) {
    for (unsigned seed : {1U, 2U, 3U}) {
      SCOPED_TRACE(std::to_string(actuators) + " actuators, seed " + std::to_string(seed));
      const StepStreamHeader header = test::step_header(actuators, seed == 3 ? 1e-4 : 1e-3);
      const auto periods = test::random_periods(header, 3000, seed);
      const std::string path = step_stream_path(dir.path().string());
      ASSERT_TRUE(write_stream(path, header, periods));
      StepStreamReader reader;
      auto opened = reader.open(path);
      ASSERT_TRUE(opened) << opened.error().message;
      EXPECT_EQ(reader.header().actuators, actuators);
      EXPECT_EQ(reader.header().period_s, header.period_s);
      EXPECT_EQ(reader.period_ns(), seed == 3 ? 100'000 : 1'000'000);
      EXPECT_EQ(reader.header().step_mm, header.step_mm);
      EXPECT_EQ(reader.header().start_position, header.start_position);
      EXPECT_EQ(reader.header().machine, header.machine);
      EXPECT_EQ(reader.period_count(), 3000);
      test::expect_same_periods(read_stream(reader), periods, actuators);
      StepPeriod after;
      EXPECT_FALSE(reader.next(after));
      EXPECT_FALSE(reader.error());
    }
  }
}

TEST(StepStream, SmallStepsTakeOneBytePerActuator) {
  const test::StepTempDir dir;
  const StepStreamHeader header = test::step_header(6);
  std::vector<StepPeriod> periods(1000);
  auto position = header.start_position;
  for (long k = 0; k < 1000; ++k) {
    periods[k].index = k;
    periods[k].line = 7;
    for (int j = 0; j < 6; ++j) {
      periods[k].steps[j] = static_cast<std::int32_t>((k + j) % 127) - 63;  // −63…63, reversing
      position[j] += periods[k].steps[j];
      periods[k].position[j] = position[j];
    }
  }
  const std::string path = dir.file("steps.bin");
  ASSERT_TRUE(write_stream(path, header, periods));
  // Header, one byte per actuator and one for the (unchanged after the first) line, end record.
  const std::size_t header_bytes = 44 + 8 * 6 + header.machine.size();
  EXPECT_EQ(fs::file_size(path), header_bytes + 1000 * 7 + 24);
}

TEST(StepStream, NoPeriodsIsAValidStream) {
  const test::StepTempDir dir;
  const std::string path = dir.file("empty.bin");
  ASSERT_TRUE(write_stream(path, test::step_header(3), {}));
  StepStreamReader reader;
  ASSERT_TRUE(reader.open(path));
  EXPECT_EQ(reader.period_count(), 0);
  EXPECT_TRUE(read_stream(reader).empty());
}

TEST(StepStream, CsvAndBinaryAgree) {
  const test::StepTempDir dir;
  for (int actuators : {3, 6}) {
    const StepStreamHeader header = test::step_header(actuators);
    const auto periods = test::random_periods(header, 2000, 11U + static_cast<unsigned>(actuators));
    StepStreamWriter binary;
    StepsCsvWriter csv;
    ASSERT_TRUE(binary.open(step_stream_path(dir.path().string()), header));
    ASSERT_TRUE(csv.open(steps_csv_path(dir.path().string()), header));
    for (const StepPeriod& p : periods) {
      StepSink* sinks[] = {&binary, &csv};
      for (StepSink* sink : sinks) ASSERT_TRUE(sink->write(p));
    }
    ASSERT_TRUE(binary.finish());
    ASSERT_TRUE(csv.finish());
    auto table = read_steps_csv(dir.file("steps.csv"));
    ASSERT_TRUE(table) << table.error().message;
    EXPECT_EQ(table->actuators, actuators);
    StepStreamReader reader;
    ASSERT_TRUE(reader.open(dir.file("steps.bin")));
    test::expect_same_periods(read_stream(reader), table->periods, actuators);
  }
}

TEST(StepStream, TruncatedFileNamesTheFileAndTheOffset) {
  const test::StepTempDir dir;
  const StepStreamHeader header = test::step_header(6);
  const std::string path = dir.file("cut.bin");
  ASSERT_TRUE(write_stream(path, header, test::random_periods(header, 500, 5U)));
  const std::string whole = test::read_bytes(path);
  for (std::size_t size : {std::size_t{0}, std::size_t{5}, std::size_t{30}, std::size_t{100},
                           whole.size() / 2, whole.size() - 24, whole.size() - 1}) {
    SCOPED_TRACE("cut to " + std::to_string(size) + " bytes");
    test::write_bytes(path, whole.substr(0, size));
    const std::string message = step_stream_error_of(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("truncated at byte " + std::to_string(size)), std::string::npos) << message;
  }
}

TEST(StepStream, DamagedBytesAreRefusedBeforeAnythingIsRead) {
  const test::StepTempDir dir;
  const StepStreamHeader header = test::step_header(3);
  const std::string path = dir.file("damaged.bin");
  ASSERT_TRUE(write_stream(path, header, test::random_periods(header, 500, 6U)));
  std::string bytes = test::read_bytes(path);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
  test::write_bytes(path, bytes);
  StepStreamReader reader;
  auto opened = reader.open(path);
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::bad_input);
  EXPECT_NE(opened.error().message.find(path + ": corrupt at byte"), std::string::npos)
      << opened.error().message;
  EXPECT_NE(opened.error().message.find("checksum"), std::string::npos) << opened.error().message;
}

TEST(StepStream, DecodingErrorsNameTheByteOffset) {
  const test::StepTempDir dir;
  StepStreamHeader header = test::step_header(1);
  header.machine = "m.yaml";
  const std::size_t data_begin = 44 + 8 + 6;
  StepPeriod big;
  big.steps[0] = 1 << 30;  // a 5-byte varint
  big.position[0] = header.start_position[0] + big.steps[0];
  const std::string path = dir.file("bad.bin");
  ASSERT_TRUE(write_stream(path, header, {big}));
  const std::string good = test::read_bytes(path);
  ASSERT_EQ(good.size(), data_begin + 5 + 1 + 24);

  std::string overlong = good;  // the step's last byte says "more follows": 6 bytes for 32 bits
  overlong[data_begin + 4] = static_cast<char>(overlong[data_begin + 4] | 0x80);
  reseal(overlong);
  test::write_bytes(path, overlong);
  std::string message = step_stream_error_of(path);
  EXPECT_NE(message.find(path + ": corrupt at byte " + std::to_string(data_begin) + ": period 0"),
            std::string::npos)
      << message;

  std::string one_more = good;  // claims two periods where the data hold one
  put_u64(one_more, good.size() - 16, 2);
  test::write_bytes(path, one_more);
  message = step_stream_error_of(path);
  EXPECT_NE(
      message.find("corrupt at byte " + std::to_string(data_begin + 6) + ": period 1 runs into the end"),
      std::string::npos)
      << message;

  std::string one_less = good;  // claims none: six bytes left over
  put_u64(one_less, good.size() - 16, 0);
  test::write_bytes(path, one_less);
  message = step_stream_error_of(path);
  EXPECT_NE(message.find("corrupt at byte " + std::to_string(data_begin) + ": 6 bytes after the last"),
            std::string::npos)
      << message;
}

TEST(StepStream, MissingOrForeignFilesAreNamed) {
  const test::StepTempDir dir;
  StepStreamReader reader;
  auto missing = reader.open(dir.file("none.bin"));
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::io);
  EXPECT_NE(missing.error().message.find(dir.file("none.bin")), std::string::npos);
  test::write_bytes(dir.file("text.bin"), "period,time_s,line\n0,0.001,1\n");
  auto foreign = reader.open(dir.file("text.bin"));
  ASSERT_FALSE(foreign);
  EXPECT_NE(foreign.error().message.find("not a pkm step stream"), std::string::npos)
      << foreign.error().message;
}

TEST(StepStream, AnAbandonedWriterLeavesNoFile) {
  const test::StepTempDir dir;
  const StepStreamHeader header = test::step_header(6);
  {
    StepStreamWriter writer;
    ASSERT_TRUE(writer.open(dir.file("steps.bin"), header));
    // Past the first megabyte, so that part of it has reached the temporary file.
    for (const StepPeriod& p : test::random_periods(header, 200'000, 8U)) ASSERT_TRUE(writer.write(p));
  }
  EXPECT_EQ(dir.entries(), 0);
}

TEST(StepStream, TheWriterRefusesPeriodsThatDoNotFollow) {
  const test::StepTempDir dir;
  const StepStreamHeader header = test::step_header(3);
  auto periods = test::random_periods(header, 10, 9U);
  {
    StepStreamWriter writer;
    ASSERT_TRUE(writer.open(dir.file("steps.bin"), header));
    ASSERT_TRUE(writer.write(periods[0]));
    StepPeriod wrong = periods[1];
    wrong.position[2] += 1;
    auto refused = writer.write(wrong);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("period 1, actuator 3"), std::string::npos)
        << refused.error().message;
    EXPECT_FALSE(writer.finish());
  }
  {
    StepStreamWriter writer;
    ASSERT_TRUE(writer.open(dir.file("steps.bin"), header));
    auto refused = writer.write(periods[1]);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("consecutive"), std::string::npos) << refused.error().message;
  }
  EXPECT_EQ(dir.entries(), 0);
  StepStreamWriter writer;
  for (int actuators : {0, kMaxActuators + 1}) {
    StepStreamHeader bad = header;
    bad.actuators = actuators;
    EXPECT_FALSE(writer.open(dir.file("steps.bin"), bad));
  }
  StepStreamHeader no_period = header;
  no_period.period_s = 0.0;
  EXPECT_FALSE(writer.open(dir.file("steps.bin"), no_period));
  EXPECT_EQ(dir.entries(), 0);
}

TEST(StepStream, Crc32IsTheIeeeChecksum) {
  EXPECT_EQ(step_stream_crc32("123456789", 9), 0xCBF43926U);  // the standard check value
  EXPECT_EQ(step_stream_crc32("6789", 4, step_stream_crc32("12345", 5)), 0xCBF43926U);
}

}  // namespace
}  // namespace pkm::interpolation
