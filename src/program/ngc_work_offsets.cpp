// Work offsets ↔ parameters, and the transform between program and work coordinates.
#include "program/ngc_work_offsets.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "program/ngc_parameter_store.hpp"

namespace pkm::program::ngc {

namespace {

Eigen::Matrix3d rotation_z(double angle_deg) {
  return Eigen::AngleAxisd(angle_deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

void read_six(const ParameterStore& parameters, int first, Eigen::Vector3d& xyz_mm,
              Eigen::Vector3d& abc_deg) {
  for (int i = 0; i < 3; ++i) {
    xyz_mm[i] = parameters.get(first + i);
    abc_deg[i] = parameters.get(first + 3 + i);
  }
}

}  // namespace

int active_system_of(const ParameterStore& parameters) {
  // Checked before the conversion to int: a program can write any number to #5220, and converting one
  // beyond int's range is undefined.
  const double rounded = std::floor(parameters.get(parameter::active_system) + 0.5);
  return rounded >= 1.0 && rounded <= 9.0 ? static_cast<int>(rounded) : 1;
}

WorkFrame read_work_frame(const ParameterStore& parameters) {
  WorkFrame frame;
  const int system = active_system_of(parameters);
  frame.system = system;
  read_six(parameters, parameter::system_base(system), frame.g5x_mm, frame.g5x_abc_deg);
  frame.xy_rotation_deg = parameters.get(parameter::system_base(system) + 9);
  // LinuxCNC keeps the G92 parameters when G92.2 suspends the offset: only an applied G92 counts.
  if (parameters.get(parameter::g92_applied) != 0.0)
    read_six(parameters, parameter::g92, frame.g92_mm, frame.g92_abc_deg);
  return frame;
}

Eigen::Vector3d to_work_mm(const WorkFrame& frame, const Eigen::Vector3d& program_mm) {
  if (frame.xy_rotation_deg == 0.0) return frame.g5x_mm + program_mm + frame.g92_mm;
  return frame.g5x_mm + rotation_z(frame.xy_rotation_deg) * (program_mm + frame.g92_mm);
}

Eigen::Vector3d to_program_mm(const WorkFrame& frame, const Eigen::Vector3d& work_mm) {
  if (frame.xy_rotation_deg == 0.0) return work_mm - frame.g5x_mm - frame.g92_mm;
  return rotation_z(-frame.xy_rotation_deg) * (work_mm - frame.g5x_mm) - frame.g92_mm;
}

void move_to_work(const WorkFrame& frame, CanonicalMove& move) {
  move.end_mm = to_work_mm(frame, move.end_mm);
  move.center_mm = to_work_mm(frame, move.center_mm);
  if (frame.xy_rotation_deg != 0.0) {
    move.normal = rotation_z(frame.xy_rotation_deg) * move.normal;
    move.tool_axis = rotation_z(frame.xy_rotation_deg) * move.tool_axis;
  }
  move.end_abc_deg += frame.g5x_abc_deg + frame.g92_abc_deg;
}

}  // namespace pkm::program::ngc
