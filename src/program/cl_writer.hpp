#pragma once
// Writing canonical moves as APT CL data (the inverse of read_cl_data, as gcode_writer is of
// interpret_gcode): for programs whose tool axes are vectors (5-axis CAM output, which G-code's A B C cannot
// state without a machine's kinematics), such as pkm stiffness's pre-compensated program and the generated
// strategies.
//
//   $$ header comments, UNITS/MM, MULTAX/ON, then per move: RAPID before a rapid's GOTO; FEDRAT/MMPM,f when
//   the feed changes; CIRCLE/xc,yc,zc,i,j,k,r before an arc's GOTO; GOTO/x,y,z,i,j,k; DELAY/s for dwells;
//   events as "$$" comments (CL data has no M words pkm could check); FINI at the end.
//
// A move that states A B C is written with its tool axis R(A,B,C)·(0,0,1) (the spin about the axis is CL
// data's free coordinate). read_cl_data reads the text back into the same moves to the decimals written.
#include <string>
#include <vector>

#include "core/result.hpp"
#include "program/canonical_program.hpp"

namespace pkm::program {

struct ClWriteOptions {
  std::vector<std::string> header_comments;  ///< each written as "$$ text"
  int decimals_mm = 4;                       ///< of lengths and feeds, 0 to 12
  int decimals_axis = 7;                     ///< of tool-axis components, 0 to 12
};

/// The CL text of `program`, lines ending in '\n'. Errors name the source and line of the move: an arc of
/// more than one turn, inverse-time feed (G93: CL data has none), a tool length offset, a non-finite value.
Result<std::string> write_cl_data(const CanonicalProgram& program, const ClWriteOptions& options);

}  // namespace pkm::program
