// Output sets as folders that cannot mix: the manifest (command, version, inputs, files), who may replace a
// folder's set, what readers refuse, the lock, joined sets, and output targets that are not regular files.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "io/atomic_file.hpp"
#include "io/content_hash.hpp"
#include "io/output_context.hpp"
#include "io/output_manifest.hpp"
#include "io/output_set.hpp"
#include "io/version.hpp"

namespace {

namespace fs = std::filesystem;

class OutputSetManifest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("pkm_output_manifest_" + std::to_string(::getpid()) + "_" + std::string(info->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    pkm::set_output_context({});
    fs::remove_all(dir_);
  }
  static void as_command(const std::string& command, bool force = false) {
    pkm::OutputContext context;
    context.command = command;
    context.force = force;
    pkm::set_output_context(context);
  }
  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  // Writes a set of `names` (content "NAME of COMMAND") into dir/run as `command`.
  pkm::Status write_set(const std::string& command, const std::vector<std::string>& names,
                        bool force = false) {
    as_command(command, force);
    pkm::OutputSet set;
    if (auto used = set.use_directory(run().string()); !used) return used;
    for (const std::string& name : names)
      if (auto w = pkm::write_file_atomically(set.staged_path(name), name + " of " + command); !w) return w;
    return set.commit();
  }
  fs::path run() const { return dir_ / "run"; }

  fs::path dir_;
};

TEST_F(OutputSetManifest, NamesCommandVersionInputsAndFiles) {
  std::ofstream(dir_ / "m.yaml") << "type: planar2\n";
  pkm::OutputContext context;
  context.command = "plan";
  context.inputs = {{"machine", (dir_ / "m.yaml").string()}};
  pkm::set_output_context(context);
  pkm::OutputSet set;
  ASSERT_TRUE(set.use_directory(run().string()));
  ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("a.csv"), "a"));
  ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("sub/b.csv"), "b"));
  ASSERT_TRUE(set.commit());
  const auto manifest = pkm::read_output_manifest(run().string());
  ASSERT_TRUE(manifest && *manifest);
  EXPECT_EQ((*manifest)->command, "plan");
  EXPECT_TRUE((*manifest)->complete);
  EXPECT_EQ((*manifest)->pkm_version, std::string(pkm::pkm_version()));
  EXPECT_TRUE(std::regex_match((*manifest)->pkm_version, std::regex(R"(\d+\.\d+\.\d+)")));
  EXPECT_EQ((*manifest)->files, (std::vector<std::string>{"a.csv", "sub/b.csv"}));
  EXPECT_EQ((*manifest)->inputs["machine"]["fnv1a64"], *pkm::file_content_hash((dir_ / "m.yaml").string()));
  EXPECT_TRUE(pkm::check_output_set(run().string(), {"plan"}));
  EXPECT_FALSE(fs::exists(run() / ".pkm-lock"));
}

TEST_F(OutputSetManifest, FnvOfKnownBytes) {
  EXPECT_EQ(pkm::fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(pkm::fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
}

TEST_F(OutputSetManifest, AnotherCommandsSetIsRefusedUnlessForced) {
  ASSERT_TRUE(write_set("plan", {"actuators.csv", "path.csv", "summary.json"}));
  const auto refused = write_set("stiffness", {"points.csv", "summary.json"});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("holds the output of pkm plan"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("--force"), std::string::npos);
  EXPECT_EQ(read(run() / "summary.json"), "summary.json of plan");
  EXPECT_FALSE(fs::exists(run() / "points.csv"));

  ASSERT_TRUE(write_set("stiffness", {"points.csv", "summary.json"}, true));
  EXPECT_FALSE(fs::exists(run() / "actuators.csv"));  // replaced whole: nothing of the plan is left
  EXPECT_FALSE(fs::exists(run() / "path.csv"));
  EXPECT_EQ(read(run() / "summary.json"), "summary.json of stiffness");
  EXPECT_TRUE(pkm::check_output_set(run().string(), {"stiffness"}));
}

TEST_F(OutputSetManifest, ARerunReplacesItsOwnSet) {
  ASSERT_TRUE(write_set("plan", {"actuators.csv", "forces.csv"}));
  ASSERT_TRUE(write_set("plan", {"actuators.csv"}));
  EXPECT_FALSE(fs::exists(run() / "forces.csv"));  // the earlier run's extra file goes with its set
  EXPECT_TRUE(pkm::check_output_set(run().string(), {"plan"}));
}

TEST_F(OutputSetManifest, FilesOfNoSetAreRefusedAndNeverDeleted) {
  fs::create_directories(run());
  std::ofstream(run() / "notes.txt") << "mine";
  const auto refused = write_set("plan", {"a.csv"});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("notes.txt is in no pkm output set"), std::string::npos)
      << refused.error().message;
  EXPECT_FALSE(fs::exists(run() / "a.csv"));
  ASSERT_TRUE(write_set("plan", {"a.csv"}, true));  // --force writes beside it, and deletes nothing of it
  EXPECT_EQ(read(run() / "notes.txt"), "mine");
  EXPECT_EQ(read(run() / "a.csv"), "a.csv of plan");
  const auto mixed = pkm::check_output_set(run().string(), {"plan"});  // a reader still sees the mix
  ASSERT_FALSE(mixed);
  EXPECT_NE(mixed.error().message.find("notes.txt"), std::string::npos) << mixed.error().message;
}

TEST_F(OutputSetManifest, ReadersRefuseMixedForeignAndIncompleteSets) {
  fs::create_directories(run());
  std::ofstream(run() / "summary.json") << "{}";
  auto checked = pkm::check_output_set(run().string(), {"plan"});
  ASSERT_FALSE(checked);
  EXPECT_NE(checked.error().message.find("no " + (run() / "manifest.json").string()), std::string::npos);
  fs::remove(run() / "summary.json");

  ASSERT_TRUE(write_set("plan", {"actuators.csv", "summary.json"}));
  checked = pkm::check_output_set(run().string(), {"servo", "interpolate"});
  ASSERT_FALSE(checked);
  EXPECT_NE(checked.error().message.find("holds the output of pkm plan, not of pkm servo or pkm interpolate"),
            std::string::npos)
      << checked.error().message;

  std::ofstream(run() / "points.csv") << "stray";
  checked = pkm::check_output_set(run().string(), {"plan"});
  ASSERT_FALSE(checked);
  EXPECT_NE(checked.error().message.find((run() / "points.csv").string() + ": not in"), std::string::npos)
      << checked.error().message;
  fs::remove(run() / "points.csv");

  fs::remove(run() / "actuators.csv");
  checked = pkm::check_output_set(run().string(), {"plan"});
  ASSERT_FALSE(checked);
  EXPECT_NE(checked.error().message.find((run() / "actuators.csv").string() + ": listed in"),
            std::string::npos)
      << checked.error().message;

  auto manifest = pkm::new_output_manifest("plan", {"summary.json"});
  manifest.command = "plan";
  manifest.complete = false;
  ASSERT_TRUE(pkm::write_output_manifest(run().string(), manifest));
  checked = pkm::check_output_set(run().string(), {"plan"});
  ASSERT_FALSE(checked);
  EXPECT_NE(checked.error().message.find("incomplete"), std::string::npos) << checked.error().message;
  EXPECT_TRUE(write_set("plan", {"actuators.csv"}));  // and the next run replaces it
  EXPECT_FALSE(fs::exists(run() / "summary.json"));
}

TEST_F(OutputSetManifest, ALockedFolderIsRefusedAtOnce) {
  ASSERT_TRUE(write_set("plan", {"a.csv"}));
  pkm::FolderLock other;  // another run holding the folder
  ASSERT_TRUE(other.acquire(run().string()));
  const auto refused = write_set("plan", {"a.csv", "b.csv"});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("another pkm run is writing it"), std::string::npos)
      << refused.error().message;
  EXPECT_FALSE(fs::exists(run() / "b.csv"));
  other.release();
  EXPECT_TRUE(write_set("plan", {"a.csv", "b.csv"}));
}

TEST_F(OutputSetManifest, AJoinedSetKeepsItsCommandAndListsTheAddedFiles) {
  ASSERT_TRUE(write_set("plan", {"actuators.csv"}));
  as_command("servo");
  pkm::OutputSet set;
  ASSERT_TRUE(set.join_directory(run().string(), {"plan"}));
  ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("servo.csv"), "servo"));
  ASSERT_TRUE(set.commit());
  const auto manifest = pkm::read_output_manifest(run().string());
  ASSERT_TRUE(manifest && *manifest);
  EXPECT_EQ((*manifest)->command, "plan");
  EXPECT_EQ((*manifest)->files, (std::vector<std::string>{"actuators.csv", "servo.csv"}));
  EXPECT_EQ((*manifest)->joined.at(0)["command"], "servo");
  EXPECT_TRUE(pkm::check_output_set(run().string(), {"plan"}));

  {
    pkm::OutputSet wrong;  // holds the lock until it goes
    EXPECT_FALSE(wrong.join_directory(run().string(), {"interpolate"}));
  }

  pkm::OutputSet again;  // the same command joining again: one entry for it, not two
  ASSERT_TRUE(again.join_directory(run().string(), {"plan"}));
  ASSERT_TRUE(pkm::write_file_atomically(again.staged_path("servo.csv"), "servo again"));
  ASSERT_TRUE(again.commit());
  const auto rejoined = pkm::read_output_manifest(run().string());
  ASSERT_TRUE(rejoined && *rejoined);
  EXPECT_EQ((*rejoined)->joined.size(), 1u);
}

TEST_F(OutputSetManifest, AFileOfTheSetItselfIsRefusedAsAnotherTarget) {
  as_command("plan");
  pkm::OutputSet set;
  ASSERT_TRUE(set.use_directory(run().string()));
  ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("actuators.csv"), "a"));
  const auto page = set.stage_file((run() / "actuators.csv").string());
  ASSERT_FALSE(page);
  EXPECT_NE(page.error().message.find("own output set"), std::string::npos) << page.error().message;
  EXPECT_FALSE(set.stage_file((run() / "manifest.json").string()));
  const auto beside = set.stage_file((run() / "report.html").string());  // beside them is fine, and listed
  ASSERT_TRUE(beside);
  ASSERT_TRUE(pkm::write_file_atomically(*beside, "page"));
  ASSERT_TRUE(set.commit());
  EXPECT_TRUE(pkm::check_output_set(run().string(), {"plan"}));
}

// Private device nodes (we run as root); the system's /dev is never touched.
TEST_F(OutputSetManifest, DevicesAreWrittenThroughAndUnreadFifosRefusedNeverReplaced) {
  const fs::path null_node = dir_ / "null", full_node = dir_ / "full", fifo = dir_ / "fifo";
  if (::mknod(null_node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0 ||
      ::mknod(full_node.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0)
    GTEST_SKIP() << "mknod needs root";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  const auto is_char = [](const fs::path& p) { return fs::is_character_file(fs::symlink_status(p)); };

  EXPECT_TRUE(pkm::write_file_atomically(null_node.string(), "text"));
  const auto full = pkm::write_file_atomically(full_node.string(), "text");
  ASSERT_FALSE(full);
  EXPECT_NE(full.error().message.find("No space left on device"), std::string::npos) << full.error().message;
  const auto refused = pkm::write_file_atomically(fifo.string(), "text");
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("a FIFO with no reader"), std::string::npos)
      << refused.error().message;

  as_command("plan");
  {
    pkm::OutputSet set;
    ASSERT_TRUE(set.use_directory(run().string()));
    ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("a.csv"), "a"));
    const auto page = set.stage_file(null_node.string());
    ASSERT_TRUE(page);
    ASSERT_TRUE(pkm::write_file_atomically(*page, "page"));
    EXPECT_TRUE(set.commit());
  }
  {
    pkm::OutputSet set;
    ASSERT_TRUE(set.use_directory(run().string()));
    ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("a.csv"), "b"));
    const auto page = set.stage_file(full_node.string());
    ASSERT_TRUE(page);
    ASSERT_TRUE(pkm::write_file_atomically(*page, "page"));
    EXPECT_FALSE(set.commit());
  }
  {
    pkm::OutputSet set;  // a FIFO nobody reads: refused at the commit, without waiting for a reader
    ASSERT_TRUE(set.use_directory(run().string()));
    ASSERT_TRUE(pkm::write_file_atomically(set.staged_path("a.csv"), "c"));
    const auto page = set.stage_file(fifo.string());
    ASSERT_TRUE(page);
    const auto committed = set.commit();
    ASSERT_FALSE(committed);
    EXPECT_NE(committed.error().message.find("a FIFO with no reader"), std::string::npos)
        << committed.error().message;
  }
  EXPECT_EQ(read(run() / "a.csv"), "a");  // the full device failed before anything was replaced
  EXPECT_TRUE(is_char(null_node));
  EXPECT_TRUE(is_char(full_node));
  EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

}  // namespace
