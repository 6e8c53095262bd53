// Every input the fuzzers found to crash, hang, leak or hit undefined behaviour (fuzz/regressions/NAME/*,
// NAME = the harness: gcode, cl, machine, load, steps_csv, steps_bin) replayed through the harness's own
// entry point (fuzz/fuzz_entries.hpp). The library must answer each with a result or an error and never
// throw; the sanitizer build (make sanitize) also catches a return of the memory error or the UB itself.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fuzz_entries.hpp"
#include "source_paths.hpp"

namespace {

std::string fuzz_regression_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

TEST(FuzzRegressions, EveryReproducerGivesAResultOrAnError) {
  const std::filesystem::path root = pkm::test::source_path("fuzz/regressions");
  ASSERT_TRUE(std::filesystem::is_directory(root)) << root;
  int replayed = 0;
  for (const auto& folder : std::filesystem::directory_iterator(root)) {
    if (!folder.is_directory()) continue;
    const std::string name = folder.path().filename().string();
    const auto entry = pkm::fuzz::entry_for(name);
    ASSERT_NE(entry, nullptr) << "fuzz/regressions/" << name << " names no harness";
    for (const auto& file : std::filesystem::directory_iterator(folder.path())) {
      if (!file.is_regular_file()) continue;
      SCOPED_TRACE(file.path().string());
      const std::string bytes = fuzz_regression_bytes(file.path());
      EXPECT_NO_THROW(entry(bytes));
      ++replayed;
    }
  }
  EXPECT_GT(replayed, 0);
  RecordProperty("replayed", replayed);
}

}  // namespace
