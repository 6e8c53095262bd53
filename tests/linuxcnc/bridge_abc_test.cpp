// LinuxCNC's A B C through pkmkins are G-code's angles, R = Rz(C)·Ry(B)·Rx(A), whatever convention the
// machine file uses for its own poses: the module's inverse of (X, Y, Z, A, B, C) is pkm's IK of the pose
// built from that product, on a krylov hexapod (ch5) and an abc one (LinuxCNC's genhexkins geometry), and its
// forward kinematics give the same A B C back. `pkm plan` reads a program's A B C the same way
// (docs/planning.md), so a program moves the same in pkm and on the controller.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/pose.hpp"
#include "core/rotation.hpp"
#include "core/units.hpp"
#include "machine/machine.hpp"
#include "machine/mechanism.hpp"
#include "pkmkins_bridge.h"
#include "test_support.hpp"

namespace pkm {
namespace {

struct AbcBridgeFree {
  void operator()(pkmkins_machine* m) const { pkmkins_free(m); }
};
using AbcBridgeHandle = std::unique_ptr<pkmkins_machine, AbcBridgeFree>;

AbcBridgeHandle abc_bridge_load(const std::string& path, std::string* message = nullptr) {
  char error[1024] = "";
  AbcBridgeHandle handle(pkmkins_load(path.c_str(), error, sizeof error));
  if (message != nullptr) *message = error;
  return handle;
}

// The pose of LinuxCNC's world (mm, deg), with the rotation as the literal product of G-code's A B C: built
// apart from the library's convention code, so the test does not check that code against itself.
Pose abc_pose_of_world(const double world[6]) {
  Pose pose;
  pose.position_mm = Eigen::Vector3d(world[0], world[1], world[2]);
  pose.rotation =
      rot_z(rad_from_deg(world[5])) * rot_y(rad_from_deg(world[4])) * rot_x(rad_from_deg(world[3]));
  return pose;
}

std::vector<double> abc_pkm_joints(const Mechanism& mech, const Pose& pose) {
  const auto q = mech.inverse(pose);
  if (!q) return {};
  return std::vector<double>(q->data(), q->data() + q->size());
}

TEST(PkmkinsBridgeAbc, InverseIsPkmIkOfTheAbcPoseOnRandomPoses) {
  for (const char* file : {"hexapod_ch5.yaml", "hexapod_genhexkins.yaml"}) {
    SCOPED_TRACE(file);
    const Machine machine = test::machine_from_example(std::string("examples/machines/") + file);
    const Mechanism& mech = *machine.mechanism;
    std::string message;
    const AbcBridgeHandle m =
        abc_bridge_load(test::source_path(std::string("examples/machines/") + file), &message);
    ASSERT_NE(m, nullptr) << message;
    double home[6];
    std::vector<double> joints(6);
    ASSERT_EQ(pkmkins_home(m.get(), home, joints.data()), 0);
    std::mt19937_64 rng(7351);
    int solved = 0;
    for (int k = 0; k < 400; ++k) {
      double world[6];
      for (int i = 0; i < 6; ++i)
        world[i] = home[i] + (i < 3 ? test::uniform(rng, -40.0, 40.0) : test::uniform(rng, -12.0, 12.0));
      const std::vector<double> expected = abc_pkm_joints(mech, abc_pose_of_world(world));
      if (expected.empty()) {
        EXPECT_EQ(pkmkins_inverse(m.get(), world, joints.data()), -1) << "pose " << k;
        continue;
      }
      ASSERT_EQ(pkmkins_inverse(m.get(), world, joints.data()), 0) << "pose " << k;
      for (std::size_t j = 0; j < 6; ++j) EXPECT_NEAR(joints[j], expected[j], 1e-9) << "pose " << k;
      ++solved;
    }
    EXPECT_GE(solved, 300);
  }
}

// The case that showed the two meanings apart: program X20 Y-10 Z-5 A4 on the ch5 hexapod (program zero at
// z = 700 mm). Read as krylov angles, A would be ψ (a yaw about z) and the struts would be mm away.
TEST(PkmkinsBridgeAbc, AProgramsTiltIsGcodesNotTheMachineFilesConvention) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Mechanism& mech = *machine.mechanism;
  ASSERT_EQ(mech.convention(), AngleConvention::krylov);
  const AbcBridgeHandle m = abc_bridge_load(test::source_path("examples/machines/hexapod_ch5.yaml"));
  ASSERT_NE(m, nullptr);
  const double world[6] = {20.0, -10.0, 695.0, 4.0, 0.0, 0.0};
  double joints[6];
  ASSERT_EQ(pkmkins_inverse(m.get(), world, joints), 0);
  const std::vector<double> abc = abc_pkm_joints(mech, abc_pose_of_world(world));
  PoseVector krylov;
  krylov << 20.0, -10.0, 695.0, rad_from_deg(4.0), 0.0, 0.0;
  const std::vector<double> machine_angles =
      abc_pkm_joints(mech, pose_from_vector(AngleConvention::krylov, krylov));
  ASSERT_EQ(abc.size(), 6u);
  ASSERT_EQ(machine_angles.size(), 6u);
  double apart_mm = 0.0;
  for (std::size_t j = 0; j < 6; ++j) {
    EXPECT_NEAR(joints[j], abc[j], 1e-9) << "joint " << j;
    apart_mm = std::max(apart_mm, std::abs(joints[j] - machine_angles[j]));
  }
  EXPECT_GT(apart_mm, 10.0);

  // Forward kinematics of those joints: the same A B C, the tilt about X.
  double found[6];
  ASSERT_EQ(pkmkins_forward(m.get(), joints, found), 0);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(found[i], world[i], 1e-8) << "coordinate " << i;
}

// The forward kinematics answer in A B C too: on the krylov hexapod, a five-axis move walked there and back
// in small steps comes back at every step as the A B C it was commanded with (turns past ±180° are
// bridge_test.cpp's, on the rotopod).
TEST(PkmkinsBridgeAbc, ForwardReturnsTheCommandedAbcAlongAWalk) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const AbcBridgeHandle m = abc_bridge_load(test::source_path("examples/machines/hexapod_ch5.yaml"));
  ASSERT_NE(m, nullptr);
  double world[6];
  double joints[6];
  ASSERT_EQ(pkmkins_home(m.get(), world, joints), 0);
  for (int step = 0; step <= 80; ++step) {
    const double t = step <= 40 ? step / 40.0 : (80 - step) / 40.0;
    const double target[6] = {10.0 * t, -5.0 * t, 700.0 + 4.0 * t, 6.0 * t, -5.0 * t, 9.0 * t};
    ASSERT_EQ(pkmkins_inverse(m.get(), target, joints), 0) << "step " << step;
    double found[6];
    ASSERT_EQ(pkmkins_forward(m.get(), joints, found), 0) << "step " << step;
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(found[i], target[i], 1e-8) << "step " << step << " coord " << i;
  }
}

// A tripod controls Z and two tilts of its own convention; only in abc are they LinuxCNC's A and B, so a
// krylov tripod is refused with a message that says what to write.
TEST(PkmkinsBridgeAbc, APartlyControlledMachineOutsideAbcIsRefused) {
  std::ifstream in(test::source_path("examples/machines/tripod.yaml"), std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string line = "angles: abc";
  const std::size_t at = text.find(line);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, line.size(), "angles: krylov");
  const auto dir = std::filesystem::temp_directory_path() / "pkm_bridge_abc_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "tripod_krylov.yaml").string();
  std::ofstream(path, std::ios::binary) << text;
  std::string message;
  EXPECT_EQ(abc_bridge_load(path, &message), nullptr);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("angles: abc"), std::string::npos) << message;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace pkm
