// The guarded input reader: directories, devices and files over the cap are refused by name with the reason
// (once std::ios_failure or std::bad_alloc aborted pkm); a byte-order mark is dropped and a lone CR ends a
// line.
#include "io/input_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

fs::path input_file_test_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("pkm_input_file_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(InputFile, RefusesADirectoryByName) {
  const fs::path dir = input_file_test_dir("directory");
  const auto text = pkm::read_input_file(dir.string(), "part program");
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().code, pkm::ErrorCode::io);
  EXPECT_EQ(text.error().message, dir.string() + ": cannot read part program: is a directory");
  fs::remove_all(dir);
}

TEST(InputFile, RefusesADeviceBeforeReadingIt) {
  const auto text = pkm::read_input_file("/dev/zero", "machine file");
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().message, "/dev/zero: cannot read machine file: is a device, not a regular file");
}

TEST(InputFile, RefusesAFileOverTheCapNamingIt) {
  const fs::path dir = input_file_test_dir("large");
  const fs::path file = dir / "big.ngc";
  { std::ofstream(file) << "G0 X1\n"; }
  fs::resize_file(file, pkm::kMaxInputFileBytes + 1);  // sparse: no disk space used
  const auto text = pkm::read_input_file(file.string(), "part program");
  ASSERT_FALSE(text);
  EXPECT_NE(text.error().message.find("more than the 256 MiB pkm reads"), std::string::npos)
      << text.error().message;
  // Streamed readers take any size.
  EXPECT_TRUE(pkm::check_input_file(file.string(), "run data", pkm::InputReading::streamed));
  fs::remove_all(dir);
}

TEST(InputFile, NamesTheSystemReasonForAMissingFile) {
  const auto text = pkm::read_input_file("/nonexistent/prog.ngc", "part program");
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().message,
            "/nonexistent/prog.ngc: cannot read part program: No such file or directory");
}

TEST(InputFile, ReadsBytesUnchanged) {
  const fs::path dir = input_file_test_dir("bytes");
  const std::string bytes(
      "\xEF\xBB\xBF"
      "a\rb\r\n\0c",
      10);
  { std::ofstream(dir / "f", std::ios::binary) << bytes; }
  const auto raw = pkm::read_input_file((dir / "f").string(), "file");
  ASSERT_TRUE(raw);
  EXPECT_EQ(*raw, bytes);
  const auto text = pkm::read_text_input((dir / "f").string(), "file");
  ASSERT_TRUE(text);
  EXPECT_EQ(*text, std::string("a\nb\r\n\0c", 7));
  fs::remove_all(dir);
}

TEST(InputFile, TextNormalisationKeepsCrLfAndOffsets) {
  EXPECT_EQ(pkm::normalize_text_input("G1\rG2\r\nG3\r"), "G1\nG2\r\nG3\n");
  EXPECT_EQ(pkm::normalize_text_input("\xEF\xBB\xBF"), "");
  EXPECT_EQ(pkm::normalize_text_input("x\xEF\xBB\xBF"), "x\xEF\xBB\xBF");  // only a leading mark
}

}  // namespace
