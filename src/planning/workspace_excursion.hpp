#pragma once
// Where a program leaves its machine's workspace, reported whole. Refused at its first sample past a limit,
// a program says nothing of how far it goes on: a pocket that leaves at Y 129 mm by 0.17 mm may go on to
// Y 235 mm. The user who must move the part needs every excursion (from which line to which), the largest
// excess of each limit, and, where one exists, the translation of the program that brings all of it inside.
//
// The scan walks the planning samples with the inverse kinematics and the position limits only (no caps);
// the translation is searched by NLopt's Sbplx on the largest excess over a thinned copy of the samples,
// then checked on every sample.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "machine/machine.hpp"
#include "path/path.hpp"
#include "program/canonical_program.hpp"

namespace pkm::planning {

/// The largest excess of one limit over the whole program.
struct LimitExcess {
  std::string limit;    ///< the machine-file key: "actuator_min", "actuator_max", "base_joint_max_deg",
                        ///< "platform_joint_max_deg", or "reach" (no actuator setting reaches the pose)
  int index = 0;        ///< 1-based actuator or joint (0 for "reach")
  double excess = 0.0;  ///< beyond the limit, in `unit` ("reach": the samples out of reach)
  std::string unit;     ///< "mm", "deg", or "samples"
  int line = 0;         ///< program line where it is largest
};

/// One stretch of consecutive samples outside the workspace.
struct Excursion {
  int first_line = 0;
  int last_line = 0;
  double length_mm = 0.0;  ///< along the path
};

struct WorkspaceExcursions {
  std::vector<Excursion> excursions;  ///< in program order
  std::vector<LimitExcess> largest;   ///< one per limit broken
  /// A translation of the program (program coordinates, mm) that brings every sample inside, if one within
  /// the search range does; added to motion.program_origin_mm it is the new program zero.
  std::optional<Eigen::Vector3d> offset_mm;
};

/// The samples `s` (path parameter) on their `segment`s, scanned for everything outside the workspace.
WorkspaceExcursions find_excursions(const Machine& machine, const path::Path& path,
                                    const std::vector<double>& s, const std::vector<int>& segment);

/// The excursions in words, for the message after the first limit's: "the program is outside the workspace
/// from line 12 to line 40 (86.0 mm of path); largest excess: actuator_max 3.2 mm (actuator 4, line 31); …".
std::string describe_excursions(const WorkspaceExcursions& found);

/// The same as JSON text (for `--json`): {"excursions": [...], "largest": [...], "offset_mm": [x, y,
/// z]|null}.
std::string excursions_json(const WorkspaceExcursions& found);

}  // namespace pkm::planning
