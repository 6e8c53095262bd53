// program_coordinates: a work-frame move back in its program's own numbers.
#include "program/canonical_program.hpp"

#include "program/ngc_work_offsets.hpp"

namespace pkm::program {

ProgramCoordinates program_coordinates(const CanonicalProgram& program, const CanonicalMove& move) {
  const std::size_t index = static_cast<std::size_t>(move.frame);
  if (index == 0 || index >= program.frames.size()) return {move.end_mm, move.center_mm, move.end_abc_deg};
  const WorkFrame& frame = program.frames[index];
  return {ngc::to_program_mm(frame, move.end_mm), ngc::to_program_mm(frame, move.center_mm),
          move.end_abc_deg - frame.g5x_abc_deg - frame.g92_abc_deg};
}

}  // namespace pkm::program
