#pragma once
// A surface tool path (surface_strategies.hpp) as canonical moves with the surface normal as the tool axis,
// ready for the planner or for program::write_cl_data (APT CL data, GOTO/x,y,z,i,j,k). The tool comes down
// onto the first point of a piece that is not joined to the previous one, and leaves the path's last point,
// by rapids along the tool axis, coming to rest on the surface in between (a dwell of 0 s): rapids carry no
// cutting load, so the approach and the retract do not enter the path's surface error, while every fed move
// (passes and links) runs on the surface and does.
#include "path/surface_strategies.hpp"
#include "program/canonical_program.hpp"

namespace pkm::path {

struct SurfaceProgramOptions {
  double feed_mm_min = 1200.0;  ///< along the passes and links, > 0
  double clearance_mm = 5.0;    ///< approach and retract distance along the tool axis, ≥ 0
};

/// The moves, numbered 1, 2, … as their `line` (written as CL data they get the text's lines).
program::CanonicalProgram surface_program(const SurfaceToolPath& path, const SurfaceProgramOptions& options);

}  // namespace pkm::path
