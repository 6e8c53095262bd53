// Golden outputs: what `pkm plan` and `pkm interpolate` write for the shipped examples stays the same through
// refactoring (when the kernel and the pipeline are recut, the numbers must not move).
//
// Every file the command writes is compared byte for byte through its size and 64-bit FNV-1a hash (the
// outputs are the same under the Release and the sanitizer builds: same compiler, no FMA contraction on
// x86-64's baseline); summary.json is compared key by key, numbers to 1e-12 relative, with the per-run timing
// keys left out and the source directory stripped from paths, so that a change shows which figure moved.
//
// An intended change of the outputs is recorded by running the suite with PKM_UPDATE_GOLDEN=1 (it rewrites
// tests/golden/data/ and passes); review the diff of the summaries before committing it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

struct GoldenCase {
  std::string name;     ///< test and data-file name
  std::string command;  ///< plan or interpolate
  std::string program;  ///< under examples/programs
  std::string machine;  ///< under examples/machines
  /// A run that must be refused: the exit code and what the message says after "PROGRAM:LINE: " (no data
  /// file, no output folder). Empty: a run whose outputs are the golden data.
  int refused_exit = 0;
  int refused_line = 0;
  std::string refusal;
};

// gtest names a failing case by this, not by its bytes.
void PrintTo(const GoldenCase& golden_case, std::ostream* out) {
  *out << golden_case.name;
}

std::vector<GoldenCase> golden_cases() {
  std::vector<GoldenCase> cases;
  auto stem = [](const std::string& file) { return file.substr(0, file.find('.')); };
  for (const std::string machine : {"hexaglide", "hexapod_ch5", "hexapod_genhexkins", "hexapod_refined",
                                    "planar3", "rotopod", "tricept", "triglide"}) {
    for (const std::string program : {"ch5_line.ngc", "helix.ngc"}) {
      if (machine == "planar3" && program == "helix.ngc") continue;  // refused below: it moves Z
      cases.push_back({"plan_" + machine + "_" + stem(program), "plan", program, machine, 0, 0, ""});
    }
  }
  cases.push_back({"plan_tripod_tripod_tilt", "plan", "tripod_tilt.ngc", "tripod", 0, 0, ""});
  for (const std::string program : {"circle.ngc", "pocket.ngc", "planar_circle.ngc", "ball_end_5axis.cl"}) {
    cases.push_back({"plan_hexapod_ch5_" + stem(program), "plan", program, "hexapod_ch5", 0, 0, ""});
  }
  // Refused, with the line: a tripod cannot move X; a planar machine cannot move Z; the ch3 hexapods' files
  // give no program origin, so program Z0 is their base plane, where the actuators' motion leaves the path
  // (another assembly mode); the planar 2-DOF machine's line crosses the singular line through its base
  // joints.
  const std::string uncontrolled = "is not a controlled coordinate";
  const std::string off_path = "off the path";
  cases.push_back(
      {"refused_plan_tripod_ch5_line", "plan", "ch5_line.ngc", "tripod", 2, 5, "X " + uncontrolled});
  cases.push_back({"refused_plan_tripod_helix", "plan", "helix.ngc", "tripod", 2, 7, "X " + uncontrolled});
  cases.push_back({"refused_plan_planar2_helix", "plan", "helix.ngc", "planar2", 2, 6, "Z " + uncontrolled});
  cases.push_back({"refused_plan_planar3_helix", "plan", "helix.ngc", "planar3", 2, 6, "Z " + uncontrolled});
  cases.push_back({"refused_plan_planar2_ch5_line", "plan", "ch5_line.ngc", "planar2", 3, 0, off_path});
  for (const std::string machine : {"hexapod_ch3", "hexapod_ch3_delta30"}) {
    for (const std::string program : {"ch5_line.ngc", "helix.ngc"})
      cases.push_back(
          {"refused_plan_" + machine + "_" + stem(program), "plan", program, machine, 3, 0, off_path});
  }
  cases.push_back({"refused_interpolate_tripod_ch5_line", "interpolate", "ch5_line.ngc", "tripod", 2, 5,
                   "X " + uncontrolled});
  // interpolate where it runs through today (the ch3 hexapods, the genhexkins example and the planar 2-DOF
  // mechanism stop on ch5_line.ngc where the path meets a near-singular pose: see docs/interpolation.md).
  for (const std::string machine :
       {"hexaglide", "hexapod_ch5", "hexapod_refined", "planar3", "rotopod", "tricept", "triglide"}) {
    cases.push_back(
        {"interpolate_" + machine + "_ch5_line", "interpolate", "ch5_line.ngc", machine, 0, 0, ""});
  }
  for (const std::string program : {"helix.ngc", "pocket.ngc"}) {
    cases.push_back(
        {"interpolate_hexapod_ch5_" + stem(program), "interpolate", program, "hexapod_ch5", 0, 0, ""});
  }
  return cases;
}

std::uint64_t fnv1a64(const std::string& bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// Per-run figures (the clock) and the build's version, not outputs of the computation.
bool volatile_key(const std::string& key) {
  return key.find("_us") != std::string::npos || key.find("period_time") != std::string::npos ||
         key == "pkm_version";
}

// Paths in the summary name the checkout; the comparison keeps what follows the source directory.
nlohmann::json normalised(const nlohmann::json& value, const std::string& source_dir) {
  if (value.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, item] : value.items()) {
      if (!volatile_key(key)) out[key] = normalised(item, source_dir);
    }
    return out;
  }
  if (value.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& item : value) out.push_back(normalised(item, source_dir));
    return out;
  }
  if (value.is_string()) {
    std::string text = value.get<std::string>();
    for (std::size_t at = text.find(source_dir); at != std::string::npos; at = text.find(source_dir)) {
      text.erase(at, source_dir.size());
    }
    return text;
  }
  return value;
}

// Numbers to 1e-12 relative (1e-300 absolute for zeros); everything else exactly. Adds one failure per
// difference, naming the JSON path.
void expect_same(const nlohmann::json& expected, const nlohmann::json& actual, const std::string& where) {
  if (expected.is_number() && actual.is_number()) {
    const double e = expected.get<double>();
    const double a = actual.get<double>();
    const double scale = std::max({std::abs(e), std::abs(a), 1e-300});
    EXPECT_LE(std::abs(e - a), 1e-12 * scale) << where << ": expected " << e << ", now " << a;
    return;
  }
  if (expected.is_object() && actual.is_object()) {
    for (const auto& [key, item] : expected.items()) {
      if (!actual.contains(key)) {
        ADD_FAILURE() << where << "/" << key << ": missing now";
        continue;
      }
      expect_same(item, actual[key], where + "/" + key);
    }
    for (const auto& [key, item] : actual.items()) {
      if (!expected.contains(key)) ADD_FAILURE() << where << "/" << key << ": new key " << item.dump();
    }
    return;
  }
  if (expected.is_array() && actual.is_array() && expected.size() == actual.size()) {
    for (std::size_t i = 0; i < expected.size(); ++i) {
      expect_same(expected[i], actual[i], where + "/" + std::to_string(i));
    }
    return;
  }
  EXPECT_EQ(expected, actual) << where;
}

class GoldenOutputs : public testing::TestWithParam<GoldenCase> {};

TEST_P(GoldenOutputs, AreUnchanged) {
  const GoldenCase& c = GetParam();
  const fs::path out = fs::path(testing::TempDir()) / ("pkm_golden_" + c.name);
  fs::remove_all(out);
  // From the source directory with relative paths: the files name the program and the machine (steps.bin's
  // header, under its checksum), and must not depend on where the project is checked out.
  // Plans write their servo-rate tables as CSV here: the golden data are the CSV files' bytes.
  const std::string tables = c.command == "plan" ? " --tables csv" : "";
  const auto run = test::run_pkm_in(test::source_path(""), c.command + " examples/programs/" + c.program +
                                                               " --machine examples/machines/" + c.machine +
                                                               ".yaml" + tables + " --out " + out.string());
  if (c.refused_exit != 0) {
    EXPECT_EQ(run.exit_code, c.refused_exit) << run.out;
    const std::string at = "examples/programs/" + c.program + ":" +
                           (c.refused_line > 0 ? std::to_string(c.refused_line) + ":" : "");
    EXPECT_NE(run.out.find(at), std::string::npos) << run.out;
    EXPECT_NE(run.out.find(c.refusal), std::string::npos) << run.out;
    EXPECT_FALSE(fs::exists(out)) << "a refused run writes nothing";
    return;
  }
  ASSERT_EQ(run.exit_code, 0) << run.out;

  nlohmann::json actual;
  std::vector<std::string> names;
  // manifest.json names the run's files, inputs and version: a record of the set, not an output to compare.
  for (const auto& entry : fs::directory_iterator(out))
    if (entry.path().filename() != "manifest.json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  const std::string source_dir = test::source_path("");
  for (const std::string& name : names) {
    const std::string bytes = read_bytes(out / name);
    if (name == "summary.json") {
      actual["summary"] = normalised(nlohmann::json::parse(bytes), source_dir);
    } else {
      std::ostringstream hash;
      hash << std::hex << fnv1a64(bytes);
      actual["files"][name] = {{"bytes", bytes.size()}, {"fnv1a64", hash.str()}};
    }
  }
  fs::remove_all(out);

  const fs::path golden = test::source_path("tests/golden/data/" + c.name + ".json");
  if (const char* update = std::getenv("PKM_UPDATE_GOLDEN");
      update != nullptr && std::string(update) == "1") {
    fs::create_directories(golden.parent_path());
    std::ofstream(golden) << actual.dump(1) << "\n";
    return;
  }
  ASSERT_TRUE(fs::exists(golden)) << golden << " is missing: run the suite with PKM_UPDATE_GOLDEN=1";
  const nlohmann::json expected = nlohmann::json::parse(read_bytes(golden));
  // The summary first: where a file's hash changed, the figure that moved is the useful message.
  expect_same(expected["summary"], actual["summary"], "summary.json");
  for (const auto& [name, file] : expected["files"].items()) {
    ASSERT_TRUE(actual["files"].contains(name)) << name << " is no longer written";
    EXPECT_EQ(file, actual["files"][name])
        << name << " changed (" << c.command << " " << c.program << " on " << c.machine << ")";
  }
  EXPECT_EQ(expected["files"].size(), actual["files"].size()) << "files written: " << actual["files"].dump();
}

INSTANTIATE_TEST_SUITE_P(Examples, GoldenOutputs, testing::ValuesIn(golden_cases()),
                         [](const testing::TestParamInfo<GoldenCase>& case_info) {
                           return case_info.param.name;
                         });

}  // namespace
}  // namespace pkm
