#pragma once
// The wall of an axisymmetric part for `pkm spif program --profile`: a CSV of the circle's radius against the
// depth into the sheet,
//   depth_mm,radius_mm
//   0,75
//   10,70
//   ...
// rows in increasing depth from 0, radii positive; `#` lines are comments. The planes of the forming path lie
// every step down, each circle's radius interpolated linearly between the rows (a cone is two rows; a
// hyperbolic cone, whose wall steepens with the depth, a few more).
#include <array>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace pkm {

/// (depth, radius) pairs in mm. Errors name the file, line, column and column name.
Result<std::vector<std::array<double, 2>>> read_spif_profile(const std::string& path);
/// The same from text (`source` names it in errors).
Result<std::vector<std::array<double, 2>>> parse_spif_profile(std::string_view text,
                                                              const std::string& source);

}  // namespace pkm
