// Output folders that cannot mix, run with the real pkm binary: the manifest a command writes, a command that
// refuses another command's folder (and replaces it whole with --force), readers that refuse mixed and
// foreign folders, two runs into one folder at once, a run stopped by SIGTERM or SIGINT, output targets that
// are devices or FIFOs (private nodes made here, never the system's /dev), and --version, --help and an
// unknown command.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"
#include "io/content_hash.hpp"
#include "io/folder_lock.hpp"
#include "io/output_manifest.hpp"
#include "io/version.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

fs::path outsets_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_outsets_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string outsets_machine() {
  return test::source_path("examples/machines/hexapod_ch5.yaml");
}

std::string outsets_plan(const fs::path& out, const std::string& extra = "") {
  return "plan " + test::source_path("examples/programs/ch5_line.ngc") + " --machine " + outsets_machine() +
         " --no-path-error --tables csv --out " + out.string() + " " + extra;
}

std::string outsets_stiffness(const fs::path& out, const std::string& extra = "") {
  return "stiffness " + test::source_path("examples/programs/ch5_line.ngc") + " --machine " +
         outsets_machine() + " --load tangential=500 --step-mm 10 --out " + out.string() + " " + extra;
}

std::string outsets_read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every file under `root` with its bytes, for "unchanged".
std::map<std::string, std::string> outsets_snapshot(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    files[fs::relative(e.path(), root).string()] = e.is_regular_file() ? outsets_read(e.path()) : "<other>";
  return files;
}

// pkm's temporaries and lock under `root`: a finished or stopped run leaves none.
std::vector<std::string> outsets_leftovers(const fs::path& root) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string name = e.path().filename().string();
    if (name.find(".pkm-staging") != std::string::npos || name.find(".tmp-") != std::string::npos ||
        name.find(".old-") != std::string::npos || name == kFolderLockName)
      found.push_back(e.path().string());
  }
  return found;
}

nlohmann::json outsets_manifest(const fs::path& folder) {
  return nlohmann::json::parse(outsets_read(folder / "manifest.json"));
}

// pkm started in the background (exec'ed by the shell, so that the pid is pkm's own).
pid_t outsets_spawn(const std::string& args, const fs::path& stderr_file) {
  const std::string command =
      "exec " + test::pkm_binary_path() + " " + args + " >/dev/null 2>" + stderr_file.string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

int outsets_wait(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(OutputSets, VersionHelpAndUnknownCommand) {
  const auto version = test::run_pkm("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, "pkm " + std::string(pkm_version()) + "\n");

  const auto unknown = test::run_pkm("foo");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.out.find("unknown command 'foo'"), std::string::npos) << unknown.out;
  EXPECT_NE(unknown.out.find("plan"), std::string::npos) << unknown.out;
  EXPECT_EQ(unknown.out.find("A subcommand is required"), std::string::npos) << unknown.out;

  const auto help = test::run_pkm("--help");
  EXPECT_EQ(help.exit_code, 0);
  std::size_t at = 0;
  for (const char* group : {"Plan and run", "Analyse", "Machine", "Calibration", "Tools"}) {
    EXPECT_NE(help.out.find(std::string(group) + ":"), std::string::npos) << group << "\n" << help.out;
    at = help.out.find(std::string(group) + ":\n    pkm ", at);  // its example, in order
    EXPECT_NE(at, std::string::npos) << group << "\n" << help.out;
  }
}

TEST(OutputSets, APlanFolderHasItsManifest) {
  const fs::path t = outsets_dir("manifest");
  const auto run = test::run_pkm(outsets_plan(t / "run"));
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const nlohmann::json manifest = outsets_manifest(t / "run");
  EXPECT_EQ(manifest["command"], "plan");
  EXPECT_EQ(manifest["pkm_version"], std::string(pkm_version()));
  EXPECT_EQ(manifest["complete"], true);
  EXPECT_EQ(manifest["files"], nlohmann::json({"actuators.csv", "path.csv", "summary.json"}));
  EXPECT_EQ(manifest["inputs"]["machine"]["fnv1a64"], *file_content_hash(outsets_machine()));
  const auto summary = nlohmann::json::parse(outsets_read(t / "run" / "summary.json"));
  EXPECT_EQ(summary["pkm_version"], std::string(pkm_version()));  // the same one version everywhere
  EXPECT_EQ(manifest["inputs"]["program"]["fnv1a64"],
            *file_content_hash(test::source_path("examples/programs/ch5_line.ngc")));
  EXPECT_TRUE(outsets_leftovers(t).empty());
  fs::remove_all(t);
}

TEST(OutputSets, AnotherCommandsFolderIsRefusedThenReplacedWholeWithForce) {
  const fs::path t = outsets_dir("force");
  ASSERT_EQ(test::run_pkm(outsets_plan(t / "run")).exit_code, 0);
  const auto before = outsets_snapshot(t / "run");
  const auto refused = test::run_pkm(outsets_stiffness(t / "run"));
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  EXPECT_NE(refused.out.find((t / "run").string()), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("holds the output of pkm plan"), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("--force"), std::string::npos) << refused.out;
  EXPECT_EQ(outsets_snapshot(t / "run"), before);

  const auto forced = test::run_pkm(outsets_stiffness(t / "run", "--force"));
  ASSERT_EQ(forced.exit_code, 0) << forced.out;
  EXPECT_FALSE(fs::exists(t / "run" / "actuators.csv"));
  EXPECT_FALSE(fs::exists(t / "run" / "path.csv"));
  EXPECT_TRUE(fs::exists(t / "run" / "points.csv"));
  EXPECT_EQ(outsets_manifest(t / "run")["command"], "stiffness");
  EXPECT_TRUE(check_output_set((t / "run").string(), {"stiffness"}));

  const auto rerun = test::run_pkm(outsets_stiffness(t / "run"));  // its own folder: replaced, no --force
  EXPECT_EQ(rerun.exit_code, 0) << rerun.out;
  EXPECT_TRUE(outsets_leftovers(t).empty());
  fs::remove_all(t);
}

TEST(OutputSets, ReadersRefuseMixedAndForeignFolders) {
  const fs::path t = outsets_dir("readers");
  ASSERT_EQ(test::run_pkm(outsets_plan(t / "run")).exit_code, 0);
  ASSERT_EQ(test::run_pkm(outsets_stiffness(t / "stiff")).exit_code, 0);

  // pkm servo needs a plan: the plan's files under another command's manifest are refused, naming the folder.
  fs::copy(t / "run", t / "relabelled");
  nlohmann::json relabelled = outsets_manifest(t / "relabelled");
  relabelled["command"] = "stiffness";
  std::ofstream(t / "relabelled" / "manifest.json") << relabelled.dump();
  const auto foreign =
      test::run_pkm("servo " + (t / "relabelled").string() + " --machine " + outsets_machine());
  EXPECT_EQ(foreign.exit_code, 2) << foreign.out;
  EXPECT_NE(
      foreign.out.find((t / "relabelled").string() + ": holds the output of pkm stiffness, not of pkm plan"),
      std::string::npos)
      << foreign.out;

  // A file of another run dropped into the plan's folder makes it a mixed set.
  std::ofstream(t / "run" / "deflection.csv") << "time_s\n";
  const auto mixed = test::run_pkm("servo " + (t / "run").string() + " --machine " + outsets_machine());
  EXPECT_EQ(mixed.exit_code, 2) << mixed.out;
  EXPECT_NE(mixed.out.find((t / "run" / "deflection.csv").string() + ": not in"), std::string::npos)
      << mixed.out;
  fs::remove(t / "run" / "deflection.csv");

  // Without its manifest the folder is no complete set.
  const fs::path bare = t / "bare";
  fs::create_directories(bare);
  for (const char* name : {"actuators.csv", "path.csv", "summary.json"})
    fs::copy(t / "run" / name, bare / name);
  const auto no_manifest = test::run_pkm("servo " + bare.string() + " --machine " + outsets_machine());
  EXPECT_EQ(no_manifest.exit_code, 2) << no_manifest.out;
  EXPECT_NE(no_manifest.out.find((bare / "manifest.json").string()), std::string::npos) << no_manifest.out;

  // pkm servo beside the plan joins its set; the folder still reads as one plan.
  const auto servo = test::run_pkm("servo " + (t / "run").string() + " --machine " + outsets_machine());
  ASSERT_EQ(servo.exit_code, 0) << servo.out;
  EXPECT_EQ(outsets_manifest(t / "run")["command"], "plan");
  EXPECT_TRUE(check_output_set((t / "run").string(), {"plan"}));
  EXPECT_EQ(outsets_manifest(t / "run")["joined"][0]["command"], "servo");
  EXPECT_TRUE(outsets_leftovers(t).empty());
  fs::remove_all(t);
}

#if PKM_REPORT_PAGE
TEST(OutputSets, ReportChecksTheFolderAndItsPageJoinsTheSet) {
  const fs::path t = outsets_dir("report");
  ASSERT_EQ(test::run_pkm(outsets_plan(t / "run")).exit_code, 0);
  const auto page = test::run_pkm("report " + (t / "run").string());
  ASSERT_EQ(page.exit_code, 0) << page.out;
  EXPECT_TRUE(check_output_set((t / "run").string(), {"plan"}));
  EXPECT_NE(outsets_manifest(t / "run")["files"].dump().find("report.html"), std::string::npos);

  std::ofstream(t / "run" / "forces.csv") << "time_s\n";  // another run's file beside the plan's
  const auto mixed = test::run_pkm("report " + (t / "run").string() + " --out " + (t / "r.html").string());
  EXPECT_EQ(mixed.exit_code, 2) << mixed.out;
  EXPECT_NE(mixed.out.find((t / "run" / "forces.csv").string() + ": not in"), std::string::npos) << mixed.out;
  EXPECT_FALSE(fs::exists(t / "r.html"));
  fs::remove_all(t);
}

// A single file named into a set's folder (a Bode table, a stiffness map) joins that set, so the report reads
// the folder whole with the file's plots; outside a set it is written on its own.
TEST(OutputSets, ASingleFileWrittenIntoASetsFolderJoinsTheSet) {
  const fs::path t = outsets_dir("join_file");
  ASSERT_EQ(test::run_pkm(outsets_plan(t / "run")).exit_code, 0);
  const std::string compliance =
      "compliance --machine " + outsets_machine() + " --pose 0,0,700,0,0,0 --points 40";
  const auto bode = test::run_pkm(compliance + " --bode " + (t / "run" / "bode.csv").string());
  ASSERT_EQ(bode.exit_code, 0) << bode.out;
  EXPECT_TRUE(check_output_set((t / "run").string(), {"plan"}));
  EXPECT_NE(outsets_manifest(t / "run")["files"].dump().find("bode.csv"), std::string::npos);
  const auto page = test::run_pkm("report " + (t / "run").string());
  EXPECT_EQ(page.exit_code, 0) << page.out;
  const auto alone = test::run_pkm(compliance + " --bode " + (t / "bode.csv").string());
  EXPECT_EQ(alone.exit_code, 0) << alone.out;
  EXPECT_FALSE(fs::exists(t / "manifest.json"));
  fs::remove_all(t);
}

TEST(OutputSets, AReportNamingAFileOfItsOwnSetIsRefused) {
  const fs::path t = outsets_dir("own");
  const auto run =
      test::run_pkm(outsets_plan(t / "run", "--report " + (t / "run" / "actuators.csv").string()));
  EXPECT_EQ(run.exit_code, 2) << run.out;
  EXPECT_NE(run.out.find("own output set"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(t / "run"));
  fs::remove_all(t);
}

// Every output option that takes a file, on a private /dev/null (written through), /dev/full (refused
// with the device's error) and a FIFO (refused): the node is still the same node afterwards.
TEST(OutputSets, DeviceAndFifoTargetsAreNeverReplaced) {
  const fs::path t = outsets_dir("devices");
  const fs::path null_node = t / "null", full_node = t / "full", fifo = t / "fifo";
  if (::mknod(null_node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0 ||
      ::mknod(full_node.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0)
    GTEST_SKIP() << "mknod needs root";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  fs::create_symlink(null_node, t / "link_to_null");
  ASSERT_EQ(test::run_pkm(outsets_plan(t / "run")).exit_code, 0);
  const std::string planar = " --machine " + test::source_path("examples/machines/planar3.yaml");
  const std::string optimize = "optimize " + test::source_path("examples/programs/planar_circle.ngc") +
                               planar + " --law increment --out ";
  const std::string modes_map =
      "modes --machine " + outsets_machine() + " --map --range-mm 20 --step-mm 20 --out ";
  struct DeviceCase {
    std::string args;
    int exit_code;
    std::string fragment;
  };
  const std::vector<DeviceCase> cases{
      {outsets_plan(t / "p1", "--report " + null_node.string()), 0, ""},
      {outsets_plan(t / "p2", "--report " + (t / "link_to_null").string()), 0, ""},
      {outsets_plan(t / "p3", "--report " + full_node.string()), 2, "No space left on device"},
      {outsets_plan(t / "p4", "--report " + fifo.string()), 2, "a FIFO with no reader"},
      {"report " + (t / "run").string() + " --out " + fifo.string(), 2, "a FIFO with no reader"},
      {"report " + (t / "run").string() + " --out " + full_node.string(), 2, "No space left on device"},
      {optimize + null_node.string(), 0, ""},
      {optimize + full_node.string(), 2, "No space left on device"},
      {modes_map + null_node.string(), 0, ""},
      {modes_map + fifo.string(), 2, "a FIFO with no reader"},
      {outsets_stiffness(t / "s1", "--compensate " + null_node.string()), 0, ""},
      {outsets_stiffness(t / "s2", "--compensate " + full_node.string()), 2, "No space left on device"},
  };
  for (const DeviceCase& c : cases) {
    const auto run = test::run_pkm(c.args);
    EXPECT_EQ(run.exit_code, c.exit_code) << c.args << "\n" << run.out;
    if (!c.fragment.empty()) {
      EXPECT_NE(run.out.find(c.fragment), std::string::npos) << c.args << "\n" << run.out;
    }
    struct stat status {};
    ASSERT_EQ(::lstat(null_node.c_str(), &status), 0) << c.args;
    EXPECT_TRUE(S_ISCHR(status.st_mode) && status.st_rdev == makedev(1, 3)) << c.args;
    ASSERT_EQ(::lstat(full_node.c_str(), &status), 0) << c.args;
    EXPECT_TRUE(S_ISCHR(status.st_mode) && status.st_rdev == makedev(1, 7)) << c.args;
    ASSERT_EQ(::lstat(fifo.c_str(), &status), 0) << c.args;
    EXPECT_TRUE(S_ISFIFO(status.st_mode)) << c.args;
    EXPECT_TRUE(fs::is_symlink(t / "link_to_null")) << c.args;
  }
  // /dev/stdout, here a pipe that popen reads: written through as asked.
  const auto piped = test::run_pkm("report " + (t / "run").string() + " --out /dev/stdout", false);
  EXPECT_EQ(piped.exit_code, 0);
  EXPECT_NE(piped.out.find("<html"), std::string::npos) << piped.out.substr(0, 200);
  EXPECT_FALSE(fs::exists(t / "run" / "report.html"));
  EXPECT_FALSE(fs::exists(t / "p3"));  // the refused runs wrote nothing
  EXPECT_FALSE(fs::exists(t / "p4"));
  EXPECT_TRUE(outsets_leftovers(t).empty()) << testing::PrintToString(outsets_leftovers(t));
  fs::remove_all(t);
}
#endif

TEST(OutputSets, ALockedFolderIsRefusedAndLeftAlone) {
  const fs::path t = outsets_dir("locked");
  ASSERT_EQ(test::run_pkm(outsets_plan(t / "run")).exit_code, 0);
  const auto before = outsets_snapshot(t / "run");
  {
    FolderLock other;  // as a run that is writing the folder now
    ASSERT_TRUE(other.acquire((t / "run").string()));
    const auto refused = test::run_pkm(outsets_plan(t / "run", "--rate 500"));
    EXPECT_EQ(refused.exit_code, 2) << refused.out;
    EXPECT_NE(refused.out.find("another pkm run is writing it"), std::string::npos) << refused.out;
    EXPECT_NE(refused.out.find((t / "run").string()), std::string::npos) << refused.out;
  }
  EXPECT_EQ(outsets_snapshot(t / "run"), before);
  EXPECT_TRUE(outsets_leftovers(t).empty());
  fs::remove_all(t);
}

// A program of `moves` back-and-forth lines of 100 mm at 600 mm/min: 10 s of motion each.
std::string outsets_long_program(const fs::path& t, int moves) {
  std::string text = "G21 G90 G17 G94\nG0 X-50 Y0 Z0\n";
  for (int i = 0; i < moves; ++i) text += i % 2 == 0 ? "G1 X50 F600\n" : "G1 X-50 F600\n";
  text += "M2\n";
  const fs::path file = t / "long.ngc";
  std::ofstream(file) << text;
  return file.string();
}

TEST(OutputSets, TwoRunsIntoOneFolderAtOnceEndWithOneWholeSet) {
  const fs::path t = outsets_dir("concurrent");
  const std::string program = outsets_long_program(t, 8);
  const std::string args =
      "plan " + program + " --machine " + outsets_machine() + " --tables csv --out " + (t / "run").string();
  const pid_t first = outsets_spawn(args + " --rate 2000", t / "first.err");
  const pid_t second = outsets_spawn(args + " --rate 1000", t / "second.err");
  const int first_code = outsets_wait(first), second_code = outsets_wait(second);
  int successes = 0;
  for (const auto& [code, err] :
       {std::pair{first_code, t / "first.err"}, std::pair{second_code, t / "second.err"}}) {
    const std::string text = outsets_read(err);
    if (code == 0) {
      ++successes;
    } else {
      EXPECT_EQ(code, 2) << text;
      EXPECT_NE(text.find("another pkm run is writing it"), std::string::npos) << text;
    }
  }
  EXPECT_GE(successes, 1);
  EXPECT_TRUE(check_output_set((t / "run").string(), {"plan"}));
  // One run's files: the summary's servo rate is the tick of the actuators.csv it sits beside.
  const auto summary = nlohmann::json::parse(outsets_read(t / "run" / "summary.json"));
  const auto rows = test::read_csv_rows((t / "run" / "actuators.csv").string()).rows;
  ASSERT_GE(rows.size(), 2u);
  EXPECT_NEAR(std::stod(rows[1][0]) - std::stod(rows[0][0]), 1.0 / summary["rate_hz"].get<double>(), 1e-6);
  EXPECT_TRUE(outsets_leftovers(t).empty()) << testing::PrintToString(outsets_leftovers(t));
  fs::remove_all(t);
}

// A long plan stopped while it writes its files: its staging folder goes, the previous set stays.
void outsets_stop_while_writing(int signal_number, const std::string& name) {
  const fs::path t = outsets_dir(name);
  ASSERT_EQ(test::run_pkm(outsets_plan(t / "run")).exit_code, 0);
  const auto before = outsets_snapshot(t / "run");
  const std::string program = outsets_long_program(t, 30);
  const pid_t pid = outsets_spawn(
      "plan " + program + " --machine " + outsets_machine() + " --rate 2000 --out " + (t / "run").string(),
      t / "stopped.err");
  bool staging_seen = false;
  for (int polls = 0; !staging_seen && polls < 600000; ++polls) {
    for (const auto& e : fs::directory_iterator(t / "run"))
      staging_seen = staging_seen || e.path().filename().string().rfind(".pkm-staging-", 0) == 0;
    if (::waitpid(pid, nullptr, WNOHANG) != 0) break;  // ended before we saw it: fails below
    if (!staging_seen) ::usleep(200);
  }
  ASSERT_TRUE(staging_seen) << "the run ended before it wrote: " << outsets_read(t / "stopped.err");
  ::kill(pid, signal_number);
  EXPECT_EQ(outsets_wait(pid), 128 + signal_number) << outsets_read(t / "stopped.err");
  EXPECT_TRUE(outsets_leftovers(t).empty()) << testing::PrintToString(outsets_leftovers(t));
  EXPECT_EQ(outsets_snapshot(t / "run"), before);
  fs::remove_all(t);
}

TEST(OutputSets, SigtermWhileWritingLeavesNoStagingFolder) {
  outsets_stop_while_writing(SIGTERM, "sigterm");
}

TEST(OutputSets, SigintWhileWritingLeavesNoStagingFolder) {
  outsets_stop_while_writing(SIGINT, "sigint");
}

}  // namespace
}  // namespace pkm
