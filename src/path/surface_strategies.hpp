#pragma once
// Rusanov et al.'s five machining strategies over a surface (Fig. 9 a–e; docs/strategies.md), generated
// on an ellipsoid cap (ellipsoid_cap.hpp) as tool-tip points with the surface normal as the tool axis:
//
//   zigzag        parallel lines along x, alternate directions, joined along the rim ("arbitrary" direction);
//   meridians     lines through the pole (meridian and its opposite), joined along the rim;
//   parallels     closed loops of constant height (the outline scaled down), joined by short radial links;
//   contour       closed loops at constant distance inside the outline (its offsets, trimmed where they meet
//                 themselves), joined by short links;
//   contour_loop  the same offsets as one continuous spiral: one loop at the first offset, a spiral that
//                 moves in by one step-over per turn, one loop at the last offset.
//
// A ball-end mill with its axis on the surface normal touches the surface with its tip, so the tool tip (the
// CL point) is the surface point itself: no cutter radius enters the points.
//
// The passes are drawn in the xy projection and lifted onto the surface. The step-over S and the point
// spacing P are bounds on the surface: adjacent passes lie at most S·cos(tilt_max) apart in the projection
// and points along a pass at most P·cos(tilt_max), so, as the surface rises at most tan(tilt_max) per mm,
// their distance on the surface is at most S and P. Every point of the cap is within half a step-over
// (projected) of some pass.
#include <Eigen/Core>
#include <array>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "path/ellipsoid_cap.hpp"

namespace pkm::path {

enum class SurfaceStrategy { zigzag, meridians, parallels, contour, contour_loop };

inline constexpr std::array<SurfaceStrategy, 5> kSurfaceStrategies = {
    SurfaceStrategy::zigzag, SurfaceStrategy::meridians, SurfaceStrategy::parallels, SurfaceStrategy::contour,
    SurfaceStrategy::contour_loop};

/// "zigzag", "meridians", "parallels", "contour", "contour_loop".
std::string_view strategy_name(SurfaceStrategy strategy);

struct StrategyOptions {
  double step_over_mm = 4.0;  ///< largest distance between adjacent passes on the surface, > 0
  double spacing_mm = 2.0;    ///< largest distance between successive points along a pass, > 0
};

struct SurfacePoint {
  Eigen::Vector3d position_mm;  ///< on the surface: the tool tip
  Eigen::Vector3d normal;       ///< unit outward normal: the tool axis (tip towards the spindle)
};

/// A piece of the tool path. A pass machines the surface; a link only connects the end of one pass with the
/// start of the next (it runs on the surface too, and cuts there). `joined`: the tool feeds from the previous
/// piece's last point straight to this piece's first one; otherwise it lifts off and comes down again.
struct SurfacePass {
  std::vector<SurfacePoint> points;
  bool link = false;
  bool joined = false;
};

struct SurfaceToolPath {
  SurfaceStrategy strategy = SurfaceStrategy::zigzag;
  std::vector<SurfacePass> pieces;  ///< in machining order

  std::size_t point_count() const;
};

/// Refuses a step-over or spacing that is not a positive finite length, and a cap and step-over that would
/// need more than `max_points` points (a typo such as 0.0001 mm, not a wish).
Status validate_strategy_options(const EllipsoidCap& cap, const StrategyOptions& options,
                                 std::size_t max_points = 2'000'000);

/// The tool path of `strategy` over `cap`. Checks the inputs as validate_ellipsoid_cap and
/// validate_strategy_options do.
Result<SurfaceToolPath> generate_strategy(SurfaceStrategy strategy, const EllipsoidCap& cap,
                                          const StrategyOptions& options);

}  // namespace pkm::path
