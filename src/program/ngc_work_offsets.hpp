#pragma once
// The work offsets of an RS274/NGC program as LinuxCNC keeps them, in its parameters, in the machine's units
// (mm for every pkm machine, whatever G20/G21 the program is in; angles in degrees):
//   #5161–#5169 G28 position, #5181–#5189 G30 position (machine coordinates),
//   #5210 G92 applied, #5211–#5219 G92 offset, #5220 active system (1 = G54 … 9 = G59.3),
//   #5221 + 20·(n − 1) … : system n's X Y Z A B C U V W offsets, and its XY rotation (degrees) at + 9.
// A program point p (what the program writes) is at work = g5x + Rz(θ)·(p + g92) in the machine's work
// frame, which is what pkm plans in; LinuxCNC's machine coordinates (G53, G28) add the tool length offset
// along Z on top of that.
#include <Eigen/Core>

#include "program/canonical_program.hpp"

namespace pkm::program::ngc {

class ParameterStore;

namespace parameter {
constexpr int g28 = 5161;
constexpr int g30 = 5181;
constexpr int g92_applied = 5210;
constexpr int g92 = 5211;
constexpr int active_system = 5220;
constexpr int probe = 5061;  ///< #5061–#5069 where the last probe ended, #5070 tripped
constexpr int probe_tripped = 5070;
constexpr int tool_number = 5400;
constexpr int tool_offset = 5401;  ///< #5401–#5409 X … W, #5410 diameter (machine units)
constexpr int tool_diameter = 5410;
constexpr int position = 5420;  ///< #5420–#5428 current position, program coordinates and program units
/// First parameter of coordinate system n (1 = G54 … 9 = G59.3).
constexpr int system_base(int n) {
  return 5201 + 20 * n;
}
}  // namespace parameter

/// The active coordinate system (1 = G54 … 9 = G59.3) as #5220 holds it; a value the program wrote there
/// that names none (0, 12, 1e30 …) is G54.
int active_system_of(const ParameterStore& parameters);
/// The work offsets in effect, read from the parameters, in mm and degrees.
WorkFrame read_work_frame(const ParameterStore& parameters);

/// work = g5x + Rz(θ)·(p + g92) (angles added).
Eigen::Vector3d to_work_mm(const WorkFrame& frame, const Eigen::Vector3d& program_mm);
/// p = Rz(−θ)·(work − g5x) − g92.
Eigen::Vector3d to_program_mm(const WorkFrame& frame, const Eigen::Vector3d& work_mm);
/// A move in program coordinates brought into the work frame (end, centre, arc axis, angles).
void move_to_work(const WorkFrame& frame, CanonicalMove& move);

}  // namespace pkm::program::ngc
