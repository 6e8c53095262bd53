// The C bridge of LinuxCNC's pkmkins module (linuxcnc/pkmkins_bridge.h) against pkm's own kinematics, on the
// shipped machines: home and its joints, inverse kinematics equal to Mechanism::inverse of the pose whose A B
// C are G-code's (abc, whatever the machine file's convention), forward kinematics along a path returning the
// pose, angles unwrapped across ±180 and past a full turn, failures that leave the state as it was, and load
// errors that name the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/pose.hpp"
#include "core/units.hpp"
#include "io/machine_file.hpp"
#include "io/version.hpp"
#include "machine/machine.hpp"
#include "machine/mechanism.hpp"
#include "pkmkins_bridge.h"
#include "test_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

struct BridgeFree {
  void operator()(pkmkins_machine* m) const { pkmkins_free(m); }
};
using BridgeHandle = std::unique_ptr<pkmkins_machine, BridgeFree>;

struct BridgeShipped {
  const char* file;
  const char* coordinates;  // the axis letters the machine controls
};

// Every shipped machine whose home is inside its actuator range, with the coordinates it controls.
const BridgeShipped kBridgeShipped[] = {{"hexapod_ch5.yaml", "XYZABC"},
                                        {"hexapod_genhexkins.yaml", "XYZABC"},
                                        {"hexapod_refined.yaml", "XYZABC"},
                                        {"tripod.yaml", "ZAB"},
                                        {"hexaglide.yaml", "XYZABC"},
                                        {"triglide.yaml", "XYZ"},
                                        {"rotopod.yaml", "XYZABC"},
                                        {"tricept.yaml", "XYZ"},
                                        {"planar3.yaml", "XYC"},
                                        {"planar2.yaml", "XY"}};

std::string bridge_machine_path(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

BridgeHandle bridge_load(const std::string& path, std::string* message = nullptr) {
  char error[1024] = "untouched";
  BridgeHandle handle(pkmkins_load(path.c_str(), error, sizeof error));
  if (message != nullptr) *message = error;
  return handle;
}

// LinuxCNC's world angles are G-code's A B C, R = Rz(C)·Ry(B)·Rx(A), on every machine.
constexpr AngleConvention kWorld = AngleConvention::abc;

// LinuxCNC's world (mm, deg) of a pose vector (mm, rad, abc), and back.
void bridge_world_from_vector(const PoseVector& v, double world[6]) {
  for (int i = 0; i < 6; ++i) world[i] = i < 3 ? v[i] : deg_from_rad(v[i]);
}
PoseVector bridge_vector_from_world(const double world[6]) {
  PoseVector v;
  for (int i = 0; i < 6; ++i) v[i] = i < 3 ? world[i] : rad_from_deg(world[i]);
  return v;
}

// Mechanism::inverse in LinuxCNC's joint units (mm, or deg for angular actuators).
bool bridge_pkm_joints(const Mechanism& mech, const Pose& pose, std::vector<double>& joints) {
  const auto q = mech.inverse(pose);
  if (!q) return false;
  joints.resize(static_cast<std::size_t>(q->size()));
  for (int j = 0; j < q->size(); ++j) {
    joints[static_cast<std::size_t>(j)] = mech.actuators_are_angles() ? deg_from_rad((*q)[j]) : (*q)[j];
  }
  return true;
}

std::string bridge_write_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "pkm_bridge_test";
  fs::create_directories(dir);
  const fs::path path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

std::string bridge_read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(PkmkinsBridge, ReportsThePkmVersionItWasBuiltFrom) {
  EXPECT_EQ(std::string(pkmkins_version()), std::string(pkm::pkm_version()));
}

TEST(PkmkinsBridge, EveryShippedMachineLoadsWithHomeJointsAndCoordinates) {
  for (const auto& shipped : kBridgeShipped) {
    SCOPED_TRACE(shipped.file);
    const std::string path = bridge_machine_path(shipped.file);
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + shipped.file);
    const Mechanism& mech = *machine.mechanism;
    std::string message;
    const BridgeHandle m = bridge_load(path, &message);
    ASSERT_NE(m, nullptr) << message;

    EXPECT_STREQ(pkmkins_coordinates(m.get()), shipped.coordinates);
    std::string from_mask;
    for (int i = 0; i < 6; ++i) {
      if (mech.controlled_axes().controlled[static_cast<std::size_t>(i)]) from_mask += "XYZABC"[i];
    }
    EXPECT_EQ(from_mask, shipped.coordinates);
    ASSERT_EQ(pkmkins_joint_count(m.get()), mech.actuator_count());

    double world[6];
    std::vector<double> joints(static_cast<std::size_t>(mech.actuator_count()), -1e300);
    ASSERT_EQ(pkmkins_home(m.get(), world, joints.data()), 0);
    std::vector<double> expected;
    ASSERT_TRUE(bridge_pkm_joints(mech, mech.home(), expected));
    for (std::size_t j = 0; j < expected.size(); ++j)
      EXPECT_NEAR(joints[j], expected[j], 1e-12) << "joint " << j;
    const PoseVector home = vector_from_pose(kWorld, mech.home());
    double home_world[6];
    bridge_world_from_vector(home, home_world);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(world[i], home_world[i], 1e-12) << "coordinate " << i;

    long solves = -1, failures = -1;
    int iterations = -1;
    pkmkins_forward_counts(m.get(), &solves, &failures, &iterations);
    EXPECT_EQ(solves, 0);
    EXPECT_EQ(failures, 0);
  }
}

// A random walk near home (steps of at most 0.4 mm / 0.25 deg in each controlled coordinate, kept within 3 mm
// / 2 deg of home): the bridge's inverse is pkm's, and its forward of those joints, solved pose after pose,
// returns the walked coordinates.
TEST(PkmkinsBridge, InverseAndForwardAlongARandomWalkMatchPkm) {
  std::mt19937_64 rng(20240611);
  for (const auto& shipped : kBridgeShipped) {
    SCOPED_TRACE(shipped.file);
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + shipped.file);
    const Mechanism& mech = *machine.mechanism;
    const BridgeHandle m = bridge_load(bridge_machine_path(shipped.file));
    ASSERT_NE(m, nullptr);
    const int n = mech.actuator_count();
    const AxisMask axes = mech.controlled_axes();
    const PoseVector home = vector_from_pose(kWorld, mech.home());
    // Forward kinematics converges to 1e-10 of the actuators' own unit (FkOptions): mm, or rad for carriages
    // on a circle, which is 5.7e-9 deg, and (on the rotopod's 300 mm circle) 3e-8 mm of carriage.
    const bool angular = mech.actuators_are_angles();
    const double joint_tolerance = angular ? deg_from_rad(1.2e-10) : 1e-9;
    const double pose_tolerance = angular ? 1e-7 : 1e-8;
    double world[6];
    std::vector<double> joints(static_cast<std::size_t>(n));
    ASSERT_EQ(pkmkins_home(m.get(), world, joints.data()), 0);

    PoseVector current = home;
    int solved = 0, rejected = 0;
    while (solved < 60 && rejected < 200) {
      PoseVector next = current;
      for (int i = 0; i < 6; ++i) {
        if (!axes.controlled[static_cast<std::size_t>(i)]) continue;
        const double step = i < 3 ? 0.4 : rad_from_deg(0.25);
        const double reach = i < 3 ? 3.0 : rad_from_deg(2.0);
        next[i] = std::clamp(next[i] + test::uniform(rng, -step, step), home[i] - reach, home[i] + reach);
      }
      double target[6];
      bridge_world_from_vector(next, target);
      std::vector<double> expected;
      if (!bridge_pkm_joints(mech, pose_from_vector(kWorld, next), expected)) {
        ++rejected;
        EXPECT_EQ(pkmkins_inverse(m.get(), target, joints.data()), -1);
        continue;
      }
      ASSERT_EQ(pkmkins_inverse(m.get(), target, joints.data()), 0) << "pose " << solved;
      for (int j = 0; j < n; ++j) {
        EXPECT_NEAR(joints[static_cast<std::size_t>(j)], expected[static_cast<std::size_t>(j)], 1e-12)
            << "pose " << solved << " joint " << j;
      }

      double found[6];
      ASSERT_EQ(pkmkins_forward(m.get(), joints.data(), found), 0) << "pose " << solved;
      for (int i = 0; i < 6; ++i) {
        if (axes.controlled[static_cast<std::size_t>(i)]) {
          EXPECT_NEAR(found[i], target[i], pose_tolerance) << "pose " << solved << " coordinate " << i;
        }
      }
      std::vector<double> back;
      ASSERT_TRUE(bridge_pkm_joints(mech, pose_from_vector(kWorld, bridge_vector_from_world(found)), back));
      for (int j = 0; j < n; ++j) {
        EXPECT_NEAR(back[static_cast<std::size_t>(j)], joints[static_cast<std::size_t>(j)], joint_tolerance)
            << "pose " << solved << " joint " << j;
      }
      if (::testing::Test::HasFailure()) return;
      current = next;
      ++solved;
    }
    EXPECT_GE(solved, 50) << rejected << " poses rejected";
    long solves = 0, failures = -1;
    int iterations = -1;
    pkmkins_forward_counts(m.get(), &solves, &failures, &iterations);
    EXPECT_EQ(solves, solved);
    EXPECT_EQ(failures, 0);
    EXPECT_GE(iterations, 0);
    EXPECT_LE(iterations, 60);
  }
}

// The rotopod turns its platform about z without end (every carriage follows on the circle). Turning C from 0
// to 400 deg and back to -200 deg in 2.5 deg steps, inverse kinematics keeps every carriage's joint
// continuous (on the turn of its last joint, past pkm's own window of half a turn around home), and forward
// kinematics returns C on the turn it was commanded on: 181 and not -179, 400 and not 40.
TEST(PkmkinsBridge, ForwardUnwrapsAnglesAcrossHalfAndFullTurns) {
  const Machine machine = test::machine_from_example("examples/machines/rotopod.yaml");
  const Mechanism& mech = *machine.mechanism;
  ASSERT_TRUE(mech.actuators_are_angles());
  // Newton stops at 1e-10 rad of carriage angle (FkOptions): a few 1e-8 mm or deg of pose.
  constexpr double kTolerance = 1e-7;
  const BridgeHandle m = bridge_load(bridge_machine_path("rotopod.yaml"));
  ASSERT_NE(m, nullptr);
  double world[6];
  std::vector<double> previous(6);
  ASSERT_EQ(pkmkins_home(m.get(), world, previous.data()), 0);
  const double home_c = world[5];
  ASSERT_NEAR(home_c, 0.0, 1e-12);

  std::vector<double> c_path;
  for (double c = 2.5; c <= 400.0; c += 2.5) c_path.push_back(c);
  for (double c = 397.5; c >= -200.0; c -= 2.5) c_path.push_back(c);
  const std::vector<double> home_joints = previous;
  bool beyond_half_turn = false;
  for (double c : c_path) {
    double target[6] = {world[0], world[1], world[2], 0.0, 0.0, c};
    std::vector<double> joints(6);
    ASSERT_EQ(pkmkins_inverse(m.get(), target, joints.data()), 0) << "C " << c;
    // A carriage moves a few degrees a step: no jump of a turn, whichever turn it is on.
    for (std::size_t j = 0; j < 6; ++j) {
      ASSERT_NEAR(joints[j], previous[j], 10.0) << "C " << c << " joint " << j;
      if (std::abs(joints[j] - home_joints[j]) > 180.0) beyond_half_turn = true;
    }
    double found[6];
    ASSERT_EQ(pkmkins_forward(m.get(), joints.data(), found), 0) << "C " << c;
    EXPECT_NEAR(found[5], c, kTolerance) << "C " << c;
    EXPECT_NEAR(found[3], 0.0, kTolerance) << "C " << c;
    EXPECT_NEAR(found[4], 0.0, kTolerance) << "C " << c;
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(found[i], target[i], kTolerance) << "C " << c << " coordinate " << i;
    if (::testing::Test::HasFailure()) return;
    previous = joints;
  }
  // The walk went past pkm's own IK window (half a turn around home), where its joints jump by a turn.
  EXPECT_TRUE(beyond_half_turn);

  // pkmkins_home restarts forward kinematics from home: C = 0 again, not -200.
  ASSERT_EQ(pkmkins_home(m.get(), world, previous.data()), 0);
  double found[6];
  ASSERT_EQ(pkmkins_forward(m.get(), previous.data(), found), 0);
  EXPECT_NEAR(found[5], 0.0, kTolerance);
}

TEST(PkmkinsBridge, InverseRejectsUnreachableAndNonFinitePoses) {
  for (const char* file : {"triglide.yaml", "rotopod.yaml", "hexaglide.yaml"}) {
    SCOPED_TRACE(file);
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *machine.mechanism;
    const BridgeHandle m = bridge_load(bridge_machine_path(file));
    ASSERT_NE(m, nullptr);
    double home[6];
    std::vector<double> home_joints(static_cast<std::size_t>(mech.actuator_count()));
    ASSERT_EQ(pkmkins_home(m.get(), home, home_joints.data()), 0);

    // Fixed-length struts cannot reach their guides 5 m above home: pkm agrees.
    double far[6];
    std::copy(home, home + 6, far);
    far[2] += 5000.0;
    ASSERT_FALSE(mech.inverse(pose_from_vector(kWorld, bridge_vector_from_world(far))).ok());
    std::vector<double> joints(static_cast<std::size_t>(mech.actuator_count()), 0.0);
    EXPECT_EQ(pkmkins_inverse(m.get(), far, joints.data()), -1);

    for (int i = 0; i < 6; ++i) {
      if (!mech.controlled_axes().controlled[static_cast<std::size_t>(i)]) continue;
      double bad[6];
      std::copy(home, home + 6, bad);
      bad[i] = std::numeric_limits<double>::quiet_NaN();
      std::vector<double> untouched(joints.size(), 12345.0);
      EXPECT_EQ(pkmkins_inverse(m.get(), bad, untouched.data()), -1) << "NaN coordinate " << i;
      bad[i] = std::numeric_limits<double>::infinity();
      EXPECT_EQ(pkmkins_inverse(m.get(), bad, untouched.data()), -1) << "infinite coordinate " << i;
    }

    // The failures changed nothing: forward kinematics has run no solve, and home's joints still give home.
    long solves = -1, failures = -1;
    int iterations = -1;
    pkmkins_forward_counts(m.get(), &solves, &failures, &iterations);
    EXPECT_EQ(solves, 0);
    EXPECT_EQ(failures, 0);
    ASSERT_EQ(pkmkins_inverse(m.get(), home, joints.data()), 0);
    for (std::size_t j = 0; j < joints.size(); ++j) EXPECT_EQ(joints[j], home_joints[j]);
    double found[6];
    ASSERT_EQ(pkmkins_forward(m.get(), joints.data(), found), 0);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(found[i], home[i], 1e-8);
  }
}

// NaN joints and struts of 1 mm fail, count as failures, leave world as it was, and the next good joints are
// solved from the last good pose.
TEST(PkmkinsBridge, ForwardFailuresLeaveTheLastGoodPose) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Mechanism& mech = *machine.mechanism;
  const BridgeHandle m = bridge_load(bridge_machine_path("hexapod_ch5.yaml"));
  ASSERT_NE(m, nullptr);
  double world[6];
  double joints[6];
  ASSERT_EQ(pkmkins_home(m.get(), world, joints), 0);

  // Two good steps away from home.
  double first[6] = {1.0, -0.5, 700.8, 0.3, -0.2, 0.4};
  double second[6] = {1.6, -0.9, 701.5, 0.5, -0.4, 0.7};
  double found[6];
  ASSERT_EQ(pkmkins_inverse(m.get(), first, joints), 0);
  ASSERT_EQ(pkmkins_forward(m.get(), joints, found), 0);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(found[i], first[i], 1e-8);

  long solves = 0, failures = 0;
  int iterations = 0;
  double nan_joints[6];
  std::copy(joints, joints + 6, nan_joints);
  nan_joints[3] = std::numeric_limits<double>::quiet_NaN();
  double sentinel[6] = {-1, -2, -3, -4, -5, -6};
  EXPECT_EQ(pkmkins_forward(m.get(), nan_joints, sentinel), -1);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(sentinel[i], -1.0 - i);
  pkmkins_forward_counts(m.get(), &solves, &failures, &iterations);
  EXPECT_EQ(solves, 2);
  EXPECT_EQ(failures, 1);

  const double short_struts[6] = {1, 1, 1, 1, 1, 1};
  EXPECT_EQ(pkmkins_forward(m.get(), short_struts, sentinel), -1);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(sentinel[i], -1.0 - i);
  pkmkins_forward_counts(m.get(), &solves, &failures, &iterations);
  EXPECT_EQ(solves, 3);
  EXPECT_EQ(failures, 2);

  // The next good joints are a small step from the last good pose, and solve to that step.
  ASSERT_EQ(pkmkins_inverse(m.get(), second, joints), 0);
  ASSERT_EQ(pkmkins_forward(m.get(), joints, found), 0);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(found[i], second[i], 1e-8);
  pkmkins_forward_counts(m.get(), &solves, &failures, &iterations);
  EXPECT_EQ(solves, 4);
  EXPECT_EQ(failures, 2);
  EXPECT_GT(iterations, 0);
  std::vector<double> back;
  ASSERT_TRUE(bridge_pkm_joints(mech, pose_from_vector(kWorld, bridge_vector_from_world(found)), back));
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(back[static_cast<std::size_t>(j)], joints[j], 1e-9);
}

TEST(PkmkinsBridge, LoadFailuresNameTheFile) {
  const std::string missing =
      (fs::temp_directory_path() / "pkm_bridge_test_no_such_dir" / "machine.yaml").string();
  std::string message;
  EXPECT_EQ(bridge_load(missing, &message), nullptr);
  EXPECT_NE(message.find(missing), std::string::npos) << message;

  EXPECT_EQ(bridge_load("", &message), nullptr);
  EXPECT_NE(message.find("machine="), std::string::npos) << message;

  // A wrong key on line 8 of an otherwise good machine file.
  const std::string good = bridge_read_text(bridge_machine_path("hexapod_ch5.yaml"));
  ASSERT_FALSE(good.empty());
  std::string bad_key_text;
  {
    std::istringstream lines(good);
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
      if (number == 8) bad_key_text += "strut_colour: blue\n";
      bad_key_text += line + "\n";
    }
  }
  const std::string bad_key = bridge_write_file("bad_key.yaml", bad_key_text);
  EXPECT_EQ(bridge_load(bad_key, &message), nullptr);
  EXPECT_NE(message.find(bad_key + ":8:"), std::string::npos) << message;
  EXPECT_NE(message.find("strut_colour"), std::string::npos) << message;

  // Home's struts are about 600 mm: a 500 mm actuator_max puts home out of range.
  const std::string limit_line = "  actuator_max: 900       # mm";
  const std::size_t at = good.find(limit_line);
  ASSERT_NE(at, std::string::npos);
  std::string short_text = good;
  short_text.replace(at, limit_line.size(), "  actuator_max: 500");
  const std::string short_max = bridge_write_file("short_max.yaml", short_text);
  EXPECT_EQ(bridge_load(short_max, &message), nullptr);
  EXPECT_NE(message.find("actuator_max"), std::string::npos) << message;
  EXPECT_NE(message.find(short_max), std::string::npos) << message;

  // The same file with 900 loads: the limit alone made the difference.
  const std::string good_copy = bridge_write_file("good_copy.yaml", good);
  EXPECT_NE(bridge_load(good_copy, &message), nullptr) << message;

  // The message is cut to the buffer and terminated; no buffer at all is allowed.
  char small[8];
  std::memset(small, 'x', sizeof small);
  EXPECT_EQ(pkmkins_load(missing.c_str(), small, sizeof small), nullptr);
  EXPECT_EQ(std::strlen(small), sizeof small - 1);
  EXPECT_EQ(pkmkins_load(missing.c_str(), nullptr, 0), nullptr);
  fs::remove_all(fs::temp_directory_path() / "pkm_bridge_test");
}

}  // namespace
}  // namespace pkm
