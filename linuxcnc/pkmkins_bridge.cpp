// pkm's kinematics behind the C functions of pkmkins_bridge.h: the machine file is read once, at module load;
// the servo-thread calls then use only the Mechanism interface's real-time forms (actuator_values, and
// forward_warm_quiet with a workspace made at load, which reports a failure without building a message).
//
// LinuxCNC's A, B, C are G-code's (docs/part-programs.md, "What A, B and C mean"): R = Rz(C)·Ry(B)·Rx(A), as
// `pkm plan` reads a program and as LinuxCNC's genhexkins takes them. The bridge converts them to and from
// the machine's own pose through the rotation matrix, so a machine file in any convention runs a program the
// same in pkm and on the controller.
#include "pkmkins_bridge.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <new>
#include <string>

#include "core/pose.hpp"
#include "core/units.hpp"
#include "io/version.hpp"
#include "machine/machine.hpp"
#include "machine/mechanism.hpp"
#include "module_machine.hpp"

struct pkmkins_machine {
  pkm::Machine machine;
  std::unique_ptr<pkm::FkWorkspace> workspace;
  int joints = 0;
  bool angular_joints = false;
  char coordinates[7] = {};
  // The last good forward solution: the next solve's guess, and the turn its angles are unwrapped to (in
  // LinuxCNC's abc angles, the coordinates that must stay continuous).
  pkm::Pose last_pose;
  pkm::PoseVector last_world_mm_rad = pkm::PoseVector::Zero();
  pkm::FkOptions options;
  long forward_solves = 0;
  long forward_failures = 0;
  int last_iterations = 0;
  // Angular joints (carriages on a circle) turn endlessly, but IK gives each angle within half a turn of its
  // home: the last joints LinuxCNC commanded or read keep the next ones on the same turn.
  double last_joints[pkm::kMaxActuators] = {};
  pkm::AxisMask controlled;
};

namespace {

using pkm::linuxcnc::copy_message;
using pkm::linuxcnc::load_module_machine;

// LinuxCNC's world angles, whatever the machine file's own convention.
constexpr pkm::AngleConvention kWorldConvention = pkm::AngleConvention::abc;

// A machine that controls one or two of the angles (a 3-RPS tripod: Z and two tilts) controls them as angles
// of its own convention; only in abc are they LinuxCNC's A and B. Machines that control all three angles, or
// none, convert exactly whatever their convention.
bool angles_are_gcode_angles(const pkm::Mechanism& mechanism) {
  const pkm::AxisMask axes = mechanism.controlled_axes();
  int angles = 0;
  for (std::size_t i = 3; i < 6; ++i) angles += axes.controlled[i] ? 1 : 0;
  return angles == 0 || angles == 3 || mechanism.convention() == pkm::AngleConvention::abc;
}

double joint_from_actuator(const pkmkins_machine& m, double value) {
  return m.angular_joints ? pkm::deg_from_rad(value) : value;
}
double actuator_from_joint(const pkmkins_machine& m, double value) {
  return m.angular_joints ? pkm::rad_from_deg(value) : value;
}

// The angle equal to `angle` modulo a full turn `turn` that is nearest to `reference`.
double unwrapped_near(double angle, double reference, double turn) {
  return angle + turn * std::round((reference - angle) / turn);
}

void remember_joints(pkmkins_machine& m, const double* joints) {
  for (int j = 0; j < m.joints; ++j) m.last_joints[j] = joints[j];
}

pkm::PoseVector pose_vector_from_world(const double world[6]) {
  pkm::PoseVector v;
  v << world[0], world[1], world[2], pkm::rad_from_deg(world[3]), pkm::rad_from_deg(world[4]),
      pkm::rad_from_deg(world[5]);
  return v;
}

void world_from_pose_vector(const pkm::PoseVector& v, double world[6]) {
  for (int i = 0; i < 3; ++i) world[i] = v[i];
  for (int i = 3; i < 6; ++i) world[i] = pkm::deg_from_rad(v[i]);
}

}  // namespace

extern "C" {

pkmkins_machine* pkmkins_load(const char* machine_file, char* error, size_t error_size) {
  try {
    auto loaded = load_module_machine(machine_file, error, error_size);
    if (!loaded) return nullptr;
    auto m = std::make_unique<pkmkins_machine>();
    m->machine = std::move(*loaded);
    const pkm::Mechanism& mechanism = *m->machine.mechanism;
    if (!angles_are_gcode_angles(mechanism)) {
      copy_message(m->machine.source + ": angles: " + std::string(pkm::to_string(mechanism.convention())) +
                       ": the machine controls only some of its angles, and they are LinuxCNC's (and "
                       "G-code's) A B C, R = Rz(C) Ry(B) Rx(A), only in the abc convention: write the "
                       "machine file with angles: abc",
                   error, error_size);
      return nullptr;
    }
    m->workspace = mechanism.make_fk_workspace();
    m->joints = mechanism.actuator_count();
    m->angular_joints = mechanism.actuators_are_angles();
    const pkm::AxisMask axes = mechanism.controlled_axes();
    m->controlled = axes;
    int n = 0;
    for (int i = 0; i < 6; ++i) {
      if (axes.controlled[static_cast<std::size_t>(i)]) m->coordinates[n++] = "XYZABC"[i];
    }
    m->coordinates[n] = '\0';
    m->last_pose = mechanism.home();
    m->last_world_mm_rad = pkm::vector_from_pose(kWorldConvention, mechanism.home());
    pkm::ActuatorVector home_actuators(m->joints);
    if (!mechanism.actuator_values(mechanism.home(), home_actuators.data())) {
      copy_message(m->machine.source + ": the home pose is out of the machine's reach", error, error_size);
      return nullptr;
    }
    if (auto in_range = pkm::check_actuator_range(m->machine, home_actuators); !in_range) {
      copy_message("at the home pose: " + in_range.error().message, error, error_size);
      return nullptr;
    }
    for (int j = 0; j < m->joints; ++j) m->last_joints[j] = joint_from_actuator(*m, home_actuators[j]);
    return m.release();
  } catch (const std::exception& e) {  // out of memory while loading: nothing else throws here
    copy_message(e.what(), error, error_size);
    return nullptr;
  }
}

void pkmkins_free(pkmkins_machine* machine) {
  delete machine;
}

int pkmkins_joint_count(const pkmkins_machine* machine) {
  return machine->joints;
}

const char* pkmkins_version(void) {
  return pkm::pkm_version().data();  // a literal: NUL-terminated
}

const char* pkmkins_coordinates(const pkmkins_machine* machine) {
  return machine->coordinates;
}

int pkmkins_home(pkmkins_machine* m, double world[6], double* joints) {
  const pkm::Mechanism& mechanism = *m->machine.mechanism;
  m->last_pose = mechanism.home();
  m->last_world_mm_rad = pkm::vector_from_pose(kWorldConvention, mechanism.home());
  m->workspace->reset();
  world_from_pose_vector(m->last_world_mm_rad, world);
  double actuators[pkm::kMaxActuators];
  if (!mechanism.actuator_values(mechanism.home(), actuators)) return -1;
  for (int j = 0; j < m->joints; ++j) joints[j] = joint_from_actuator(*m, actuators[j]);
  remember_joints(*m, joints);
  return 0;
}

int pkmkins_inverse(pkmkins_machine* m, const double world[6], double* joints) {
  pkm::PoseVector v = pose_vector_from_world(world);
  for (int i = 0; i < 6; ++i) {
    if (std::isfinite(v[i])) continue;
    // The coordinates the machine does not control do not enter its IK; the others must be numbers.
    if (m->controlled.controlled[static_cast<std::size_t>(i)]) return -1;
    v[i] = 0.0;
  }
  double actuators[pkm::kMaxActuators];
  if (!m->machine.mechanism->actuator_values_at(kWorldConvention, v, actuators)) return -1;
  for (int j = 0; j < m->joints; ++j) {
    if (!std::isfinite(actuators[j])) return -1;
    joints[j] = joint_from_actuator(*m, actuators[j]);
    if (m->angular_joints) joints[j] = unwrapped_near(joints[j], m->last_joints[j], 360.0);
  }
  remember_joints(*m, joints);
  return 0;
}

int pkmkins_forward(pkmkins_machine* m, const double* joints, double world[6]) {
  ++m->forward_solves;
  pkm::ActuatorVector actuators(m->joints);
  for (int j = 0; j < m->joints; ++j) actuators[j] = actuator_from_joint(*m, joints[j]);
  if (!actuators.allFinite()) {
    ++m->forward_failures;
    return -1;
  }
  pkm::FkSolution solution;
  pkm::ErrorCode failure{};  // LinuxCNC learns only that it failed: −1
  if (!m->machine.mechanism->forward_warm_quiet(actuators, m->last_pose, m->options, *m->workspace, solution,
                                                failure)) {
    ++m->forward_failures;
    return -1;
  }
  m->last_iterations = solution.iterations;
  pkm::PoseVector v = pkm::vector_from_pose(kWorldConvention, solution.pose);
  for (int i = 3; i < 6; ++i)
    v[i] = unwrapped_near(v[i], m->last_world_mm_rad[i], 2.0 * 3.14159265358979323846);
  m->last_pose = solution.pose;
  remember_joints(*m, joints);
  m->last_world_mm_rad = v;
  world_from_pose_vector(v, world);
  return 0;
}

void pkmkins_forward_counts(const pkmkins_machine* m, long* solves, long* failures, int* last_iterations) {
  *solves = m->forward_solves;
  *failures = m->forward_failures;
  *last_iterations = m->last_iterations;
}

}  // extern "C"
