// program_coordinates: a work-frame move back in its program's own numbers.
#include "program/canonical_program.hpp"

#include <Eigen/Geometry>
#include <numbers>

namespace pkm::program {

namespace {

// work = g5x + Rz(θ)·(program + g92)  ⇒  program = Rz(−θ)·(work − g5x) − g92
Eigen::Vector3d to_program(const WorkFrame& frame, const Eigen::Vector3d& work_mm) {
  const double theta = frame.xy_rotation_deg * std::numbers::pi / 180.0;
  const Eigen::AngleAxisd undo(-theta, Eigen::Vector3d::UnitZ());
  return undo * (work_mm - frame.g5x_mm) - frame.g92_mm;
}

}  // namespace

ProgramCoordinates program_coordinates(const CanonicalProgram& program, const CanonicalMove& move) {
  const std::size_t index = static_cast<std::size_t>(move.frame);
  if (index == 0 || index >= program.frames.size()) return {move.end_mm, move.center_mm, move.end_abc_deg};
  const WorkFrame& frame = program.frames[index];
  return {to_program(frame, move.end_mm), to_program(frame, move.center_mm),
          move.end_abc_deg - frame.g5x_abc_deg - frame.g92_abc_deg};
}

}  // namespace pkm::program
