// The LinuxCNC configuration writer (pipeline/linuxcnc_config.hpp) on the shipped machines: the INI's
// kinematics, joints and coordinates are the machine file's, machine.yaml is the file itself, genhexkins'
// joint coordinates give pkm's strut lengths, and every refusal names its reason and writes nothing.
#include "pipeline/linuxcnc_config.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/pose.hpp"
#include "core/units.hpp"
#include "io/machine_file.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

// A fresh, not yet existing directory under the system's temporary one, removed with everything in it at the
// end.
class LinuxcncTempDir {
 public:
  explicit LinuxcncTempDir(const std::string& name)
      : root_(fs::temp_directory_path() / ("pkm_linuxcnc_config_test_" + name)) {
    fs::remove_all(root_);
  }
  ~LinuxcncTempDir() { fs::remove_all(root_); }
  LinuxcncTempDir(const LinuxcncTempDir&) = delete;
  LinuxcncTempDir& operator=(const LinuxcncTempDir&) = delete;
  const fs::path& root() const { return root_; }

 private:
  fs::path root_;
};

std::string linuxcnc_read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// An INI file as sections of (key, value) pairs in file order (HALFILE appears more than once).
using LinuxcncIni = std::map<std::string, std::vector<std::pair<std::string, std::string>>>;

LinuxcncIni linuxcnc_parse_ini(const std::string& text) {
  LinuxcncIni ini;
  std::istringstream lines(text);
  std::string line, section;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line.front() == '[' && line.back() == ']') {
      section = line.substr(1, line.size() - 2);
      ini[section];
      continue;
    }
    const std::size_t eq = line.find(" = ");
    if (eq == std::string::npos) {
      ADD_FAILURE() << "not KEY = VALUE: " << line;
      continue;
    }
    ini[section].emplace_back(line.substr(0, eq), line.substr(eq + 3));
  }
  return ini;
}

// The one value of `key` in `section`; fails the test when there is none or more than one.
std::string linuxcnc_ini_value(const LinuxcncIni& ini, const std::string& section, const std::string& key) {
  const auto s = ini.find(section);
  if (s == ini.end()) {
    ADD_FAILURE() << "no [" << section << "]";
    return "";
  }
  std::vector<std::string> values;
  for (const auto& [k, v] : s->second) {
    if (k == key) values.push_back(v);
  }
  if (values.size() != 1) {
    ADD_FAILURE() << "[" << section << "] " << key << " appears " << values.size() << " times";
    return "";
  }
  return values[0];
}

// A number that must be the whole value.
double linuxcnc_number(const std::string& text) {
  std::size_t used = 0;
  double value = std::nan("");
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    ADD_FAILURE() << "not a number: '" << text << "'";
  }
  EXPECT_EQ(used, text.size()) << "not just a number: '" << text << "'";
  return value;
}

std::vector<double> linuxcnc_pkm_home_joints(const Machine& machine) {
  const Mechanism& mech = *machine.mechanism;
  const auto q = mech.inverse(mech.home());
  EXPECT_TRUE(q.ok());
  std::vector<double> joints;
  if (!q) return joints;
  for (int j = 0; j < q->size(); ++j) {
    joints.push_back(mech.actuators_are_angles() ? deg_from_rad((*q)[j]) : (*q)[j]);
  }
  return joints;
}

// `source` with every line containing one of `drop` removed.
std::string linuxcnc_without_lines(const std::string& source, const std::vector<std::string>& drop) {
  std::istringstream lines(source);
  std::string line, out;
  while (std::getline(lines, line)) {
    bool keep = true;
    for (const auto& d : drop) keep = keep && line.find(d) == std::string::npos;
    if (keep) out += line + "\n";
  }
  return out;
}

std::vector<std::string> linuxcnc_entries(const fs::path& dir) {
  std::vector<std::string> names;
  // The configuration's files; manifest.json only names them (the output set's own record).
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename() != "manifest.json") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(LinuxcncConfig, HexapodIniCarriesTheMachineFile) {
  const LinuxcncTempDir tmp("ch5");
  const std::string source = test::source_path("examples/machines/hexapod_ch5.yaml");
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const fs::path dir = tmp.root() / "config";
  LinuxcncConfigOptions options;
  options.out_directory = dir.string();
  const auto config = write_linuxcnc_config(machine, options);
  ASSERT_TRUE(config.ok()) << config.error().message;

  EXPECT_EQ(linuxcnc_entries(dir), (std::vector<std::string>{"drives.hal", "machine.hal", "machine.ini",
                                                             "machine.yaml", "tool.tbl"}));
  EXPECT_EQ(config->files.size(), 5u);
  EXPECT_EQ(config->coordinates, "XYZABC");
  EXPECT_EQ(config->servo_period_ns, 1000000);  // drives: period_ms: 1

  // machine.yaml is the file itself, byte for byte: pkmkins reads it at load.
  const std::string source_text = linuxcnc_read_text(source);
  ASSERT_FALSE(source_text.empty());
  EXPECT_EQ(linuxcnc_read_text(dir / "machine.yaml"), source_text);

  const LinuxcncIni ini = linuxcnc_parse_ini(linuxcnc_read_text(dir / "machine.ini"));
  const std::string abs_dir = fs::absolute(dir).lexically_normal().string();
  EXPECT_EQ(linuxcnc_ini_value(ini, "KINS", "KINEMATICS"), "pkmkins machine=" + abs_dir + "/machine.yaml");
  EXPECT_EQ(linuxcnc_ini_value(ini, "KINS", "JOINTS"), "6");
  EXPECT_EQ(linuxcnc_ini_value(ini, "TRAJ", "COORDINATES"), "X Y Z A B C");
  EXPECT_EQ(linuxcnc_ini_value(ini, "EMCMOT", "SERVO_PERIOD"), "1000000");
  EXPECT_EQ(linuxcnc_ini_value(ini, "EMCIO", "TOOL_TABLE"), "tool.tbl");
  EXPECT_TRUE(fs::is_regular_file(dir / "tool.tbl"));

  // Every joint: pkm's home strut length, the machine's limits.
  const std::vector<double> home = linuxcnc_pkm_home_joints(machine);
  ASSERT_EQ(home.size(), 6u);
  ASSERT_EQ(config->home_joints.size(), 6u);
  for (int j = 0; j < 6; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j));
    const std::string section = "JOINT_" + std::to_string(j);
    EXPECT_EQ(linuxcnc_ini_value(ini, section, "TYPE"), "LINEAR");
    EXPECT_NEAR(linuxcnc_number(linuxcnc_ini_value(ini, section, "HOME")), home[static_cast<std::size_t>(j)],
                1e-9);
    EXPECT_NEAR(config->home_joints[static_cast<std::size_t>(j)], home[static_cast<std::size_t>(j)], 1e-9);
    EXPECT_EQ(linuxcnc_number(linuxcnc_ini_value(ini, section, "MIN_LIMIT")), *machine.limits.min);
    EXPECT_EQ(linuxcnc_number(linuxcnc_ini_value(ini, section, "MAX_LIMIT")), *machine.limits.max);
    EXPECT_EQ(linuxcnc_number(linuxcnc_ini_value(ini, section, "MAX_VELOCITY")), *machine.limits.speed);
    EXPECT_EQ(linuxcnc_number(linuxcnc_ini_value(ini, section, "MAX_ACCELERATION")), *machine.limits.accel);
  }
  EXPECT_EQ(*machine.limits.min, 350.0);  // the values above are the file's, not defaults
  EXPECT_EQ(*machine.limits.max, 900.0);
  EXPECT_EQ(ini.count("JOINT_6"), 0u);
  for (const char* axis : {"AXIS_X", "AXIS_Y", "AXIS_Z", "AXIS_A", "AXIS_B", "AXIS_C"}) {
    EXPECT_EQ(ini.count(axis), 1u) << axis;
  }

  // G54 is the program origin (0, 0, 700).
  const std::string startup = linuxcnc_ini_value(ini, "RS274NGC", "RS274NGC_STARTUP_CODE");
  const std::size_t g10 = startup.find("G10 L2 P1");
  ASSERT_NE(g10, std::string::npos) << startup;
  std::istringstream words(startup.substr(g10 + 9));
  std::map<char, double> origin;
  for (std::string word; words >> word;) origin[word[0]] = linuxcnc_number(word.substr(1));
  const Eigen::Vector3d expected_origin = machine.motion.program_origin_mm;
  EXPECT_EQ(expected_origin.z(), 700.0);
  ASSERT_EQ(origin.size(), 3u) << startup;
  EXPECT_EQ(origin['X'], expected_origin.x());
  EXPECT_EQ(origin['Y'], expected_origin.y());
  EXPECT_EQ(origin['Z'], expected_origin.z());

  // machine.hal loads the kinematics and motion; drives.hal loops every joint's command back as its feedback,
  // and shows where real drives go, with this machine's steps per mm (drives.step_mm 0.001).
  EXPECT_NE(linuxcnc_read_text(dir / "machine.hal").find("loadrt [KINS]KINEMATICS"), std::string::npos);
  std::vector<std::string> hal_files;
  for (const auto& [k, v] : ini.at("HAL")) {
    if (k == "HALFILE") hal_files.push_back(v);
  }
  EXPECT_EQ(hal_files, (std::vector<std::string>{"machine.hal", "drives.hal"}));
  const std::string hal = linuxcnc_read_text(dir / "drives.hal");
  EXPECT_NE(hal.find("#   setp hm2_7i76e.0.stepgen.0N.position-scale 1000\n"), std::string::npos) << hal;
  EXPECT_NE(hal.find("#   net jN-pos-cmd joint.N.motor-pos-cmd => lcec.0.driveN.pos-cmd"), std::string::npos);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NE(hal.find(fmt::format("joint.{0}.motor-pos-cmd => joint.{0}.motor-pos-fb", j)),
              std::string::npos);
  }
  EXPECT_EQ(hal.find("joint.6."), std::string::npos);

  // Writing again over the same directory replaces the set and leaves no staging folder behind.
  const auto again = write_linuxcnc_config(machine, options);
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(linuxcnc_entries(dir), (std::vector<std::string>{"drives.hal", "machine.hal", "machine.ini",
                                                             "machine.yaml", "tool.tbl"}));

  // After LinuxCNC ran it, its parameter file (the INI's PARAMETER_FILE) is beside the configuration: writing
  // the configuration again keeps it and is not refused; a file of anyone else's still is.
  std::ofstream(dir / "pkm.var") << "5220\t1.000000\n";
  std::ofstream(dir / "pkm.var.bak") << "5220\t1.000000\n";
  const auto after_run = write_linuxcnc_config(machine, options);
  ASSERT_TRUE(after_run.ok()) << after_run.error().message;
  EXPECT_EQ(linuxcnc_entries(dir),
            (std::vector<std::string>{"drives.hal", "machine.hal", "machine.ini", "machine.yaml", "pkm.var",
                                      "pkm.var.bak", "tool.tbl"}));
  std::ofstream(dir / "notes.txt") << "mine\n";
  const auto foreign = write_linuxcnc_config(machine, options);
  ASSERT_FALSE(foreign.ok());
  EXPECT_NE(foreign.error().message.find("notes.txt"), std::string::npos) << foreign.error().message;
}

TEST(LinuxcncConfig, TripodControlsZAB) {
  const LinuxcncTempDir tmp("tripod");
  const Machine machine = test::machine_from_example("examples/machines/tripod.yaml");
  LinuxcncConfigOptions options;
  options.out_directory = (tmp.root() / "config").string();
  const auto config = write_linuxcnc_config(machine, options);
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_EQ(config->coordinates, "ZAB");
  const LinuxcncIni ini = linuxcnc_parse_ini(linuxcnc_read_text(tmp.root() / "config" / "machine.ini"));
  EXPECT_EQ(linuxcnc_ini_value(ini, "TRAJ", "COORDINATES"), "Z A B");
  EXPECT_EQ(linuxcnc_ini_value(ini, "KINS", "JOINTS"), "3");
  const std::vector<double> home = linuxcnc_pkm_home_joints(machine);
  ASSERT_EQ(home.size(), 3u);
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(linuxcnc_number(linuxcnc_ini_value(ini, "JOINT_" + std::to_string(j), "HOME")),
                home[static_cast<std::size_t>(j)], 1e-9);
  }
  EXPECT_EQ(ini.count("JOINT_3"), 0u);
  EXPECT_EQ(ini.count("AXIS_X"), 0u);
  EXPECT_EQ(ini.count("AXIS_C"), 0u);
  EXPECT_EQ(ini.count("AXIS_Z"), 1u);
  EXPECT_EQ(ini.count("AXIS_B"), 1u);
  // Only the controlled Z of the program origin (800 mm) goes into G54.
  const std::string startup = linuxcnc_ini_value(ini, "RS274NGC", "RS274NGC_STARTUP_CODE");
  EXPECT_NE(startup.find("G10 L2 P1 Z800"), std::string::npos) << startup;
  EXPECT_EQ(startup.find('X'), std::string::npos) << startup;
}

// genhexkins' base and platform joints, put through the strut-length formula of genhexkins at a pose, give
// pkm's strut lengths: at home and at a tilted, turned pose (which checks the platform joints' frame). Its
// A B C are G-code's, as pkmkins' are, so a machine file in krylov angles (ch5) is described as well.
void check_genhexkins_config(const std::string& file) {
  SCOPED_TRACE(file);
  const LinuxcncTempDir tmp("genhexkins_" + file);
  const Machine machine = test::machine_from_example("examples/machines/" + file);
  const Mechanism& mech = *machine.mechanism;
  const fs::path dir = tmp.root() / "config";
  LinuxcncConfigOptions options;
  options.out_directory = dir.string();
  options.kinematics = LinuxcncKinematics::genhexkins;
  const auto config = write_linuxcnc_config(machine, options);
  ASSERT_TRUE(config.ok()) << config.error().message;
  EXPECT_EQ(linuxcnc_entries(dir), (std::vector<std::string>{"drives.hal", "genhexkins.hal", "machine.hal",
                                                             "machine.ini", "machine.yaml", "tool.tbl"}));
  const LinuxcncIni ini = linuxcnc_parse_ini(linuxcnc_read_text(dir / "machine.ini"));
  EXPECT_EQ(linuxcnc_ini_value(ini, "KINS", "KINEMATICS"), "genhexkins");
  std::vector<std::string> hal_files;
  for (const auto& [k, v] : ini.at("HAL")) {
    if (k == "HALFILE") hal_files.push_back(v);
  }
  EXPECT_EQ(hal_files, (std::vector<std::string>{"machine.hal", "drives.hal", "genhexkins.hal"}));

  std::array<Eigen::Vector3d, 6> base, platform;
  std::array<std::array<bool, 3>, 6> base_set{}, platform_set{};
  std::istringstream lines(linuxcnc_read_text(dir / "genhexkins.hal"));
  int setps = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string setp, pin, value;
    words >> setp >> pin >> value;
    ASSERT_EQ(setp, "setp") << line;
    int j = -1;
    char part[16] = {}, axis = 0;
    ASSERT_EQ(std::sscanf(pin.c_str(), "genhexkins.%15[a-z].%d.%c", part, &j, &axis), 3) << line;
    ASSERT_TRUE(j >= 0 && j < 6 && axis >= 'x' && axis <= 'z') << line;
    const int k = axis - 'x';
    const auto jj = static_cast<std::size_t>(j);
    if (std::string(part) == "base") {
      base[jj][k] = linuxcnc_number(value);
      base_set[jj][static_cast<std::size_t>(k)] = true;
    } else {
      ASSERT_EQ(std::string(part), "platform") << line;
      platform[jj][k] = linuxcnc_number(value);
      platform_set[jj][static_cast<std::size_t>(k)] = true;
    }
    ++setps;
  }
  EXPECT_EQ(setps, 36);
  for (std::size_t j = 0; j < 6; ++j) {
    for (std::size_t k = 0; k < 3; ++k) ASSERT_TRUE(base_set[j][k] && platform_set[j][k]) << j << " " << k;
  }

  // genhexkins: R = Rz(C)·Ry(B)·Rx(A), strut j = |base_j − (R·platform_j + p)|.
  auto check_pose = [&](const PoseVector& v) {
    const Eigen::Matrix3d r = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    const Eigen::Vector3d p = v.head<3>();
    const auto q = mech.inverse(pose_from_vector(AngleConvention::abc, v));
    ASSERT_TRUE(q.ok());
    for (int j = 0; j < 6; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      EXPECT_NEAR((base[jj] - (r * platform[jj] + p)).norm(), (*q)[j], 1e-9) << "strut " << j;
    }
  };
  const PoseVector home = vector_from_pose(AngleConvention::abc, mech.home());
  EXPECT_EQ(home[2], file == "hexapod_ch5.yaml" ? 700.0 : 508.0);
  {
    SCOPED_TRACE("home");
    check_pose(home);
  }
  const std::vector<double> home_joints = linuxcnc_pkm_home_joints(machine);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(linuxcnc_number(linuxcnc_ini_value(ini, "JOINT_" + std::to_string(j), "HOME")),
                home_joints[static_cast<std::size_t>(j)], 1e-9);
  }
  {
    SCOPED_TRACE("tilted");
    PoseVector tilted = home;
    tilted[0] += 12.0;
    tilted[1] -= 7.0;
    tilted[2] += 20.0;
    tilted[3] = rad_from_deg(4.0);
    tilted[4] = rad_from_deg(-3.0);
    tilted[5] = rad_from_deg(6.0);
    check_pose(tilted);
  }
}

TEST(LinuxcncConfig, GenhexkinsJointsGivePkmStrutLengths) {
  check_genhexkins_config("hexapod_genhexkins.yaml");
  check_genhexkins_config("hexapod_ch5.yaml");
}

// LinuxCNC's A B C are G-code's: the world home of a machine whose home is tilted, in krylov angles, is
// written as the same rotation's A B C.
TEST(LinuxcncConfig, TrajHomeIsInGcodeAngles) {
  const LinuxcncTempDir tmp("tilted_home");
  fs::create_directories(tmp.root());
  std::string text = linuxcnc_read_text(test::source_path("examples/machines/hexapod_ch5.yaml"));
  const std::string home_line = "home: [0, 0, 700, 0, 0, 0]";
  const std::size_t at = text.find(home_line);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, home_line.size(), "home: [3, -2, 700, 5, 3, -4]");
  const fs::path file = tmp.root() / "tilted.yaml";
  std::ofstream(file, std::ios::binary) << text;
  auto machine = load_machine_file(file.string());
  ASSERT_TRUE(machine.ok()) << machine.error().message;
  LinuxcncConfigOptions options;
  options.out_directory = (tmp.root() / "config").string();
  const auto config = write_linuxcnc_config(*machine, options);
  ASSERT_TRUE(config.ok()) << config.error().message;
  const LinuxcncIni ini = linuxcnc_parse_ini(linuxcnc_read_text(tmp.root() / "config" / "machine.ini"));
  std::istringstream words(linuxcnc_ini_value(ini, "TRAJ", "HOME"));
  PoseVector written;
  for (int i = 0; i < 6; ++i) ASSERT_TRUE(words >> written[i]) << i;
  const PoseVector abc = vector_from_pose(AngleConvention::abc, machine->mechanism->home());
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(written[i], i < 3 ? abc[i] : deg_from_rad(abc[i]), 1e-9) << "coordinate " << i;
  EXPECT_GT(std::abs(written[3] - 5.0), 0.1);  // not the krylov ψ
  // The A axis is centred there.
  EXPECT_NEAR(linuxcnc_number(linuxcnc_ini_value(ini, "AXIS_A", "MIN_LIMIT")), written[3] - 180.0, 1e-9);
}

// A tripod controls Z and two tilts in its own convention; only in abc are they LinuxCNC's A and B.
TEST(LinuxcncConfig, TripodOutsideAbcIsRefused) {
  const LinuxcncTempDir tmp("tripod_krylov");
  fs::create_directories(tmp.root());
  std::string text = linuxcnc_read_text(test::source_path("examples/machines/tripod.yaml"));
  const std::size_t at = text.find("angles: abc");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 11, "angles: krylov");
  const fs::path file = tmp.root() / "tripod_krylov.yaml";
  std::ofstream(file, std::ios::binary) << text;
  auto machine = load_machine_file(file.string());
  ASSERT_TRUE(machine.ok()) << machine.error().message;
  LinuxcncConfigOptions options;
  options.out_directory = (tmp.root() / "config").string();
  const auto config = write_linuxcnc_config(*machine, options);
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.error().message.find("angles: abc"), std::string::npos) << config.error().message;
  EXPECT_EQ(config.error().location.key, "angles");
  EXPECT_FALSE(fs::exists(tmp.root() / "config"));
}

// Homing on switches (the textbook's search): each joint searches down at v1 to its lower boundary switch, 1
// % of the range below the software stop, latches backing off at v2 = v1 / 50, and its switch is simulated
// where the strut's length (home length at motor position 0) reaches it.
TEST(LinuxcncConfig, HomingOnSwitchesSearchesDownAndLatchesBackingOff) {
  const LinuxcncTempDir tmp("homing");
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  LinuxcncConfigOptions options;
  options.out_directory = (tmp.root() / "config").string();
  options.homing = LinuxcncHoming::switches;
  const auto config = write_linuxcnc_config(machine, options);
  ASSERT_TRUE(config.ok()) << config.error().message;
  const LinuxcncIni ini = linuxcnc_parse_ini(linuxcnc_read_text(tmp.root() / "config" / "machine.ini"));
  const std::string hal = linuxcnc_read_text(tmp.root() / "config" / "drives.hal");
  const double min = *machine.limits.min, max = *machine.limits.max, speed = *machine.limits.speed;
  ASSERT_EQ(config->homing_switches.size(), 6u);
  for (int j = 0; j < 6; ++j) {
    const std::string joint = fmt::format("JOINT_{}", j);
    const double switch_at = linuxcnc_number(linuxcnc_ini_value(ini, joint, "HOME_OFFSET"));
    EXPECT_NEAR(switch_at, min - 0.01 * (max - min), 1e-9);
    EXPECT_LT(switch_at, linuxcnc_number(linuxcnc_ini_value(ini, joint, "MIN_LIMIT")));
    const double search = linuxcnc_number(linuxcnc_ini_value(ini, joint, "HOME_SEARCH_VEL"));
    const double latch = linuxcnc_number(linuxcnc_ini_value(ini, joint, "HOME_LATCH_VEL"));
    EXPECT_DOUBLE_EQ(search, -0.25 * speed);       // down, towards the lower switch
    EXPECT_DOUBLE_EQ(latch, 0.25 * speed / 50.0);  // up, off it: v1 ≫ v2
    EXPECT_DOUBLE_EQ(linuxcnc_number(linuxcnc_ini_value(ini, joint, "HOME")), config->home_joints[j]);
    // The simulated switch at the motor position where the strut (home length at 0) reaches it.
    EXPECT_NE(hal.find(fmt::format("setp sim-home-switch.{}.home-pos {:.17g}", j,
                                   switch_at - config->home_joints[j])),
              std::string::npos);
    EXPECT_NE(
        hal.find(fmt::format("net j{0}-home-sw sim-home-switch.{0}.home-sw => joint.{0}.home-sw-in", j)),
        std::string::npos);
  }
  // trivkins has no actuators as joints: homing on switches is refused.
  options.kinematics = LinuxcncKinematics::trivkins;
  options.out_directory = (tmp.root() / "trivkins").string();
  EXPECT_FALSE(write_linuxcnc_config(machine, options).ok());
}

TEST(LinuxcncConfig, MachineWithoutActuatorLimitsIsRefused) {
  const LinuxcncTempDir tmp("no_limits");
  fs::create_directories(tmp.root());
  const std::string text =
      linuxcnc_without_lines(linuxcnc_read_text(test::source_path("examples/machines/hexapod_ch5.yaml")),
                             {"actuator_min", "actuator_max", "actuator_speed", "actuator_accel"});
  const fs::path file = tmp.root() / "no_limits.yaml";
  std::ofstream(file, std::ios::binary) << text;
  auto machine = load_machine_file(file.string());
  ASSERT_TRUE(machine.ok()) << machine.error().message;
  ASSERT_FALSE(machine->limits.min.has_value());

  LinuxcncConfigOptions options;
  const fs::path out = tmp.root() / "new" / "config";
  options.out_directory = out.string();
  const auto config = write_linuxcnc_config(*machine, options);
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.error().message.find("limits.actuator_min"), std::string::npos) << config.error().message;
  EXPECT_NE(config.error().message.find(file.string()), std::string::npos) << config.error().message;
  EXPECT_EQ(config.error().location.key, "limits.actuator_min");
  EXPECT_FALSE(fs::exists(tmp.root() / "new"));
}

TEST(LinuxcncConfig, PathWithASpaceIsRefusedAndWritesNothing) {
  const LinuxcncTempDir tmp("space");
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  LinuxcncConfigOptions options;
  options.out_directory = (tmp.root() / "my config").string();
  const auto config = write_linuxcnc_config(machine, options);
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.error().message.find("space"), std::string::npos) << config.error().message;
  EXPECT_FALSE(fs::exists(tmp.root())) << "a refused configuration created its directory";

  // genhexkins needs no path in the module's arguments, but the refusal does not depend on the kinematics.
  options.kinematics = LinuxcncKinematics::genhexkins;
  const Machine genhexkins = test::machine_from_example("examples/machines/hexapod_genhexkins.yaml");
  EXPECT_FALSE(write_linuxcnc_config(genhexkins, options).ok());
  EXPECT_FALSE(fs::exists(tmp.root()));
}

// A write that fails half way (machine.ini cannot replace a directory of that name) places none of the files
// and leaves no staging folder.
TEST(LinuxcncConfig, FailedWritePlacesNoFile) {
  const LinuxcncTempDir tmp("blocked");
  const fs::path dir = tmp.root() / "config";
  fs::create_directories(dir / "machine.ini");
  std::ofstream(dir / "machine.ini" / "keep", std::ios::binary) << "x";
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  LinuxcncConfigOptions options;
  options.out_directory = dir.string();
  const auto config = write_linuxcnc_config(machine, options);
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.error().message.find("machine.ini"), std::string::npos) << config.error().message;
  EXPECT_EQ(linuxcnc_entries(dir), std::vector<std::string>{"machine.ini"});
  EXPECT_TRUE(fs::is_regular_file(dir / "machine.ini" / "keep"));
}

// The `net` lines of a HAL text as (signal, pins) with the pins' arrows dropped.
std::map<std::string, std::vector<std::string>> linuxcnc_nets(const std::string& hal) {
  std::map<std::string, std::vector<std::string>> nets;
  std::istringstream lines(hal);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string word, signal;
    if (!(words >> word) || word != "net" || !(words >> signal)) continue;
    auto& pins = nets[signal];
    while (words >> word)
      if (word != "=>" && word != "<=") pins.push_back(word);
  }
  return nets;
}

// With --execute, pkm's executor sits between LinuxCNC's motion and the drives: each drive's command is
// LinuxCNC's or pkmexec's (a mux on pkmexec.active, pkmexec's in motor units with LinuxCNC's homing offset),
// LinuxCNC's motion is disabled while pkmexec has the drives, pkmexec takes a program only when LinuxCNC
// hands them over and follows LinuxCNC's joints in between; the drives (step or servo) read the one command
// signal.
TEST(LinuxcncConfig, ExecuteHandsTheDrivesOverThroughPkmexec) {
  const LinuxcncTempDir tmp("execute");
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  for (const LinuxcncDrives kind : {LinuxcncDrives::steps, LinuxcncDrives::servo}) {
    const fs::path dir = tmp.root() / (kind == LinuxcncDrives::steps ? "steps" : "servo");
    LinuxcncConfigOptions options;
    options.out_directory = dir.string();
    options.execute = true;
    options.drives = kind;
    const auto config = write_linuxcnc_config(machine, options);
    ASSERT_TRUE(config.ok()) << config.error().message;
    EXPECT_EQ(linuxcnc_entries(dir), (std::vector<std::string>{"drives.hal", "execute.hal", "machine.hal",
                                                               "machine.ini", "machine.yaml", "tool.tbl"}));
    const LinuxcncIni ini = linuxcnc_parse_ini(linuxcnc_read_text(dir / "machine.ini"));
    std::vector<std::string> hal_files;
    for (const auto& [k, v] : ini.at("HAL"))
      if (k == "HALFILE") hal_files.push_back(v);
    EXPECT_EQ(hal_files, (std::vector<std::string>{"machine.hal", "execute.hal", "drives.hal"}));
    EXPECT_EQ(linuxcnc_ini_value(ini, "HAL", "HALUI"), "halui");
    EXPECT_EQ(linuxcnc_ini_value(ini, "DISPLAY", "MAX_FEED_OVERRIDE"), "1.2");

    const std::string execute = linuxcnc_read_text(dir / "execute.hal");
    EXPECT_NE(execute.find(fmt::format("loadrt pkmexec machine={}/machine.yaml period_ns=1000000",
                                       fs::absolute(dir).lexically_normal().string())),
              std::string::npos)
        << execute;
    const std::string drives = linuxcnc_read_text(dir / "drives.hal");
    const auto nets = linuxcnc_nets(linuxcnc_read_text(dir / "machine.hal") + execute + drives);
    const auto has = [&](const std::string& signal, const std::string& pin) {
      const auto it = nets.find(signal);
      return it != nets.end() && std::find(it->second.begin(), it->second.end(), pin) != it->second.end();
    };
    EXPECT_TRUE(has("pkm-active", "pkmexec.active"));
    EXPECT_TRUE(has("pkm-active", "pkm-motion-off.in"));
    EXPECT_TRUE(has("pkm-motion-allowed", "motion.enable"));
    EXPECT_TRUE(has("pkm-handed-over", "pkmexec.enable"));
    EXPECT_TRUE(has("pkm-feed-override", "halui.feed-override.value"));
    EXPECT_TRUE(has("pkm-stop-now", "pkmexec.abort"));
    for (int j = 0; j < 6; ++j) {
      const std::string cmd = fmt::format("j{}-pos-cmd", j);
      EXPECT_TRUE(has(cmd, fmt::format("pkm-drive-cmd-{}.out", j))) << cmd;
      EXPECT_TRUE(has("pkm-active", fmt::format("pkm-drive-cmd-{}.sel", j)));
      EXPECT_TRUE(has(fmt::format("j{}-motion-cmd", j), fmt::format("joint.{}.motor-pos-cmd", j)));
      EXPECT_TRUE(has(fmt::format("j{}-motor-offset", j), fmt::format("joint.{}.motor-offset", j)));
      EXPECT_TRUE(has(fmt::format("j{}-joint-pos", j), fmt::format("pkmexec.{}.pos-fb", j)));
      // The drive reads the one command; LinuxCNC's motor-pos-cmd reaches it only through the mux.
      const std::string fb_signal = kind == LinuxcncDrives::steps ? cmd : fmt::format("j{}-pos-fb", j);
      EXPECT_TRUE(has(fb_signal, fmt::format("joint.{}.motor-pos-fb", j))) << drives;
      if (kind == LinuxcncDrives::servo) {
        EXPECT_TRUE(has(cmd, fmt::format("pkm-servo-{}.command", j)));
      }
    }
    EXPECT_EQ(nets.count("j6-pos-cmd"), 0u);
    // Every pin in one signal at most (HAL refuses a second link).
    std::map<std::string, int> links;
    for (const auto& [signal, pins] : nets)
      for (const std::string& pin : pins) EXPECT_EQ(++links[pin], 1) << pin << " in " << signal;
  }
  // trivkins' joints are not the actuators pkmexec moves.
  LinuxcncConfigOptions trivkins;
  trivkins.out_directory = (tmp.root() / "trivkins").string();
  trivkins.execute = true;
  trivkins.kinematics = LinuxcncKinematics::trivkins;
  const auto refused = write_linuxcnc_config(machine, trivkins);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("--execute"), std::string::npos) << refused.error().message;
  EXPECT_FALSE(fs::exists(tmp.root() / "trivkins"));
}

}  // namespace
}  // namespace pkm
