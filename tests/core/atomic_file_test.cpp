// Atomic file writing: the content arrives whole, a failure leaves neither the file nor a temporary behind
// and names the path with the system's reason.
#include "io/atomic_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

// A fresh empty directory per test, removed at the end.
class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("pkm_atomic_file_" + std::to_string(::getpid()) + "_" + std::string(info->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
  }
  int entries() const {
    return static_cast<int>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}));
  }

  fs::path dir_;
};

TEST_F(AtomicFile, WritesTheContent) {
  const fs::path path = dir_ / "out.ngc";
  std::string text = "G21 G90\n";
  text += std::string(3 << 20, 'x');  // larger than one write() may take at once on some systems
  ASSERT_TRUE(pkm::write_file_atomically(path.string(), text));
  EXPECT_EQ(read(path), text);
  EXPECT_EQ(entries(), 1);  // no temporary left
}

TEST_F(AtomicFile, ReplacesAnExistingFile) {
  const fs::path path = dir_ / "out.txt";
  ASSERT_TRUE(pkm::write_file_atomically(path.string(), "old content, longer than the new\n"));
  ASSERT_TRUE(pkm::write_file_atomically(path.string(), "new\n"));
  EXPECT_EQ(read(path), "new\n");
  EXPECT_EQ(entries(), 1);
}

TEST_F(AtomicFile, MissingDirectoryLeavesNothingAndNamesThePath) {
  const fs::path path = dir_ / "no_such_dir" / "out.ngc";
  const pkm::Status written = pkm::write_file_atomically(path.string(), "M2\n");
  ASSERT_FALSE(written);
  EXPECT_EQ(written.error().code, pkm::ErrorCode::io);
  EXPECT_NE(written.error().message.find(path.string()), std::string::npos) << written.error().message;
  EXPECT_NE(written.error().message.find("No such file or directory"), std::string::npos)
      << written.error().message;
  EXPECT_FALSE(fs::exists(dir_ / "no_such_dir"));
  EXPECT_EQ(entries(), 0);
}

TEST_F(AtomicFile, RenameOntoADirectoryFailsAndRemovesTheTemporary) {
  // The temporary is written, then the rename fails: the path is a non-empty directory.
  const fs::path path = dir_ / "taken";
  fs::create_directories(path / "inside");
  const pkm::Status written = pkm::write_file_atomically(path.string(), "text\n");
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().message.find(path.string()), std::string::npos) << written.error().message;
  EXPECT_EQ(entries(), 1);  // only the directory
}

TEST_F(AtomicFile, StagedFileNotCommittedLeavesNothing) {
  const fs::path path = dir_ / "partial.csv";
  {
    pkm::StagedFile file;
    ASSERT_TRUE(file.open(path.string()));
    ASSERT_TRUE(file.write("half of it\n"));
    EXPECT_EQ(entries(), 1);  // the temporary
  }
  EXPECT_EQ(entries(), 0);
}

}  // namespace
