#pragma once
// Forming paths for single point incremental forming (SPIF, Smirnov 2019 §3.8.1): the punch runs round
// circles in planes stepped into the sheet, each circle a little smaller (a cone with the sheet's wall
// angle), as G-code the interpreter reads like any other program. The seeds' case is the default: 21 planes
// 1.06 mm apart, the first circle R 75 mm, each next one 0.5 mm smaller, counter-clockwise (positive φ).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace pkm::program {

enum class SpifPathKind {
  planes,  ///< a full circle in each plane, a straight step down between them (contour-parallel)
  helix,   ///< each turn a helix down to the next plane, then the step to the next radius
};

struct SpifPathOptions {
  double radius_mm = 75.0;      ///< of the first circle
  double radius_step_mm = 0.5;  ///< each next circle this much smaller (the cone's wall)
  int planes = 21;
  double step_down_mm = 1.06;     ///< between planes
  bool counter_clockwise = true;  ///< G3 (positive φ), else G2
  bool depth_up = false;          ///< the planes step along +Z (a tool pointing up into the sheet), else −Z
  double z1_mm = 0.0;             ///< the first plane, program coordinates
  Eigen::Vector2d centre_mm = Eigen::Vector2d::Zero();
  double feed_mm_min = 1200.0;
  double approach_mm = 5.0;  ///< the rapid comes to this height over the first plane (on the far side)
  SpifPathKind kind = SpifPathKind::planes;
  /// The wall of an axisymmetric part as (depth, radius) rows from depth 0 (io/spif_profile_file.hpp): when
  /// given, the planes lie every step down to its deepest row and each circle's radius is the wall's there,
  /// in place of radius_mm, radius_step_mm and planes.
  std::vector<std::array<double, 2>> profile;
};

/// The program's text, its first lines saying how it was made; errors name the bad option.
Result<std::string> spif_program_text(const SpifPathOptions& options);

}  // namespace pkm::program
