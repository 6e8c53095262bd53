#pragma once
// Corner blending: where two moves meet at an angle, the path leaves the first move a distance d before the
// corner and joins the second one d after it along the cross-fade
//   C(u) = A(u) + w(u)·(B(u) − A(u)),   w(u) = 10u³ − 15u⁴ + 6u⁵,
// where A runs over the last d of the first move and B over the first d of the second. w has zero first and
// second derivatives at both ends, so position, tangent and curvature are continuous (G2) for lines, arcs and
// helices alike; d is the largest that keeps C within the path tolerance and within half of either move.
// A corner whose blend would not be regular (near a reversal the cross-fade's speed |C'(u)| vanishes) or not
// within the tolerance is an exact stop instead; so is a join where the platform's turning rate jumps and no
// blend fits. The blend is reparametrised by arc length (a monotone map, so every evaluated point lies on the
// blend) so that the planned speed along it is the tool-point speed.
#include <optional>

#include "path/path.hpp"

namespace pkm::path {

/// Replaces the corners between consecutive plain segments of `path` by blends (in place), where the segments
/// are not separated by a stop. `tolerance_mm` ≤ 0 leaves every corner as a stop.
void blend_corners(Path& path, double tolerance_mm);

/// The join of `prev` and `next`, consecutive plain segments of `path` (whose curves it holds): the blend
/// between them, with both trimmed to its ends and its table added to `path`; or nothing, with `prev` marked
/// as a stop where the corner needs one (or already was), or left as it is where the join is smooth.
std::optional<Segment> join_corner(Path& path, Segment& prev, Segment& next, double tolerance_mm);

/// A plain segment that trimming left with (almost) nothing, and no stop: left out of the path.
bool is_sliver(const Segment& segment);

/// Largest distance of the blend of segment `blend_index` from the two curves it joins (sampled).
double blend_deviation_mm(const Path& path, int blend_index);

}  // namespace pkm::path
