// Output sets: all files replace the previous ones together, or none does; nothing of a failed set remains.
#include "io/output_set.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/atomic_file.hpp"
#include "io/output_manifest.hpp"

namespace {

namespace fs = std::filesystem;

class OutputSetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("pkm_output_set_" + std::to_string(::getpid()) + "_" + std::string(info->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  // Every name under the folder, for "nothing else is there".
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) out.push_back(fs::relative(e.path(), dir_));
    std::sort(out.begin(), out.end());
    return out;
  }
  // A complete earlier set of this process's command, listing `more` files too.
  void previous_run(std::vector<std::string> more = {}) const {
    fs::create_directories(dir_ / "run");
    std::ofstream(dir_ / "run" / "a.csv") << "old a";
    std::ofstream(dir_ / "run" / "b.csv") << "old b";
    more.insert(more.end(), {"a.csv", "b.csv"});
    ASSERT_TRUE(
        pkm::write_output_manifest((dir_ / "run").string(), pkm::new_output_manifest("library", more)));
  }

  fs::path dir_;
};

TEST_F(OutputSetTest, CommitReplacesEveryFile) {
  previous_run();
  pkm::OutputSet set;
  ASSERT_TRUE(set.use_directory((dir_ / "run").string()));
  ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("a.csv"), "new a"));
  ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("b.csv"), "new b"));
  auto page = set.stage_file((dir_ / "pages" / "report.html").string());
  ASSERT_TRUE(page);
  ASSERT_TRUE(pkm::write_file_atomically(*page, "page"));
  EXPECT_EQ(read(dir_ / "run" / "a.csv"), "old a");  // nothing changes before commit()
  ASSERT_TRUE(set.commit());
  EXPECT_EQ(read(dir_ / "run" / "a.csv"), "new a");
  EXPECT_EQ(read(dir_ / "run" / "b.csv"), "new b");
  EXPECT_EQ(read(dir_ / "pages" / "report.html"), "page");
  EXPECT_EQ(names(), (std::vector<std::string>{"pages", "pages/report.html", "run", "run/a.csv", "run/b.csv",
                                               "run/manifest.json"}));
}

TEST_F(OutputSetTest, ADirectoryInTheWayLeavesThePreviousRun) {
  previous_run();
  fs::create_directories(dir_ / "run" / "c.csv");
  pkm::OutputSet set;
  ASSERT_TRUE(set.use_directory((dir_ / "run").string()));
  for (const char* name : {"a.csv", "b.csv", "c.csv"})
    ASSERT_TRUE(pkm::write_file_atomically(set.staged_path(name), "new"));
  const auto committed = set.commit();
  ASSERT_FALSE(committed);
  EXPECT_EQ(committed.error().message,
            "cannot write " + (dir_ / "run" / "c.csv").string() + ": Is a directory");
  EXPECT_EQ(read(dir_ / "run" / "a.csv"), "old a");
  EXPECT_EQ(read(dir_ / "run" / "b.csv"), "old b");
}

TEST_F(OutputSetTest, AFailedRenameRestoresTheFilesAlreadyPlaced) {
  // A previous file whose name leaves no room for the ".old-XXXXXX" suffix: moving it aside fails after
  // a.csv is already in place, so the set must put the old a.csv back.
  const std::string long_name(250, 'L');
  previous_run({long_name});
  std::ofstream(dir_ / "run" / long_name) << "old long";
  const std::string manifest_before = read(dir_ / "run" / "manifest.json");
  {
    pkm::OutputSet set;
    ASSERT_TRUE(set.use_directory((dir_ / "run").string()));
    ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("a.csv"), "new a"));
    // Written directly: a staged file's own temporary would need the suffix room the name does not leave.
    std::ofstream(set.staged_path(long_name)) << "new long";
    const auto committed = set.commit();
    ASSERT_FALSE(committed);
    EXPECT_NE(committed.error().message.find(long_name), std::string::npos);
    EXPECT_EQ(read(dir_ / "run" / "a.csv"), "old a");
    EXPECT_EQ(read(dir_ / "run" / long_name), "old long");
    EXPECT_EQ(read(dir_ / "run" / "manifest.json"), manifest_before);  // complete again, the old list
  }  // the failed set removes its staging folder
  EXPECT_EQ(names(), (std::vector<std::string>{"run", "run/" + long_name, "run/a.csv", "run/b.csv",
                                               "run/manifest.json"}));
}

TEST_F(OutputSetTest, AnAbandonedSetRemovesWhatItMade) {
  {
    pkm::OutputSet set;
    ASSERT_TRUE(set.use_directory((dir_ / "new" / "run").string()));
    ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("a.csv"), "new a"));
    ASSERT_TRUE(set.stage_file((dir_ / "other" / "report.html").string()));
  }
  EXPECT_TRUE(names().empty()) << testing::PrintToString(names());
}

TEST_F(OutputSetTest, AFileWhereTheFolderShouldBeIsNamed) {
  std::ofstream(dir_ / "run") << "a file";
  pkm::OutputSet set;
  const auto used = set.use_directory((dir_ / "run" / "deeper").string());
  ASSERT_FALSE(used);
  EXPECT_NE(used.error().message.find("is not a directory"), std::string::npos) << used.error().message;
}

}  // namespace
