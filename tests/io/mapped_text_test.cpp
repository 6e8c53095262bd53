// A mapped text file reads as read_text_input reads it (the byte-order mark dropped, lone carriage returns
// turned into line feeds), its line index points at line starts, and pages given back behind and ahead of the
// reader read again as they were.
#include "io/mapped_text.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "io/input_file.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string write_file(const std::string& name, const std::string& bytes) {
  const fs::path path = fs::temp_directory_path() / ("pkm_mapped_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}

TEST(MappedText, ReadsAsTheWholeReaderDoes) {
  for (const std::string& bytes :
       {std::string("\xEF\xBB\xBFG1 X1\r\nG1 X2\r\n"), std::string("G1 X1\rG1 X2\rM2"), std::string(""),
        std::string("M2"), std::string("G0 X0\n\n\nM2\n")}) {
    const std::string path = write_file("small.ngc", bytes);
    auto mapped = MappedText::open(path, "part program");
    ASSERT_TRUE(mapped.ok()) << mapped.error().message;
    auto whole = read_text_input(path, "part program");
    ASSERT_TRUE(whole.ok());
    EXPECT_EQ((*mapped)->text(), *whole);
    fs::remove(path);
  }
}

TEST(MappedText, GivenBackPagesReadAgainAsTheyWereAndTheIndexPointsAtLineStarts) {
  std::mt19937_64 rng(20261207);
  std::uniform_int_distribution<int> length(0, 80), letter('A', 'Z');
  std::string bytes;
  std::vector<std::size_t> starts;
  while (bytes.size() < (std::size_t{12} << 20)) {
    starts.push_back(bytes.size());
    const int n = length(rng);
    for (int i = 0; i < n; ++i) bytes.push_back(static_cast<char>(letter(rng)));
    bytes.push_back('\n');
  }
  const std::string path = write_file("long.ngc", bytes);
  auto mapped = MappedText::open(path, "part program");
  ASSERT_TRUE(mapped.ok()) << mapped.error().message;
  MappedText& text = **mapped;
  EXPECT_EQ(text.line_count(), static_cast<int>(starts.size()));
  std::uniform_int_distribution<std::size_t> at(0, bytes.size() - 1);
  for (int trial = 0; trial < 50; ++trial) {
    text.keep_around(at(rng));
    const std::size_t from = at(rng), count = std::min<std::size_t>(1 << 16, bytes.size() - from);
    ASSERT_EQ(text.text().substr(from, count), std::string_view(bytes).substr(from, count)) << trial;
  }
  ASSERT_EQ(text.text(), bytes);
  std::uniform_int_distribution<int> line(1, static_cast<int>(starts.size()));
  for (int trial = 0; trial < 200; ++trial) {
    const int l = line(rng);
    const std::size_t offset = text.offset_near_line(l);
    EXPECT_LE(offset, starts[static_cast<std::size_t>(l - 1)]) << l;
    EXPECT_TRUE(offset == 0 || bytes[offset - 1] == '\n') << l;
    EXPECT_GE(offset + (std::size_t{2000} * 82), starts[static_cast<std::size_t>(l - 1)]) << l;
  }
  fs::remove(path);
}

TEST(MappedText, RefusesWhatIsNotARegularFile) {
  auto mapped = MappedText::open(fs::temp_directory_path().string(), "part program");
  ASSERT_FALSE(mapped.ok());
  EXPECT_NE(mapped.error().message.find("is a directory"), std::string::npos) << mapped.error().message;
}

}  // namespace
}  // namespace pkm
