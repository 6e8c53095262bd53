#pragma once
// Redundant output coordinates (Smirnov 2019, ch. 3): the pose coordinates an operation leaves free.
//
//  - planar machines (planar3): the platform angle φ (C in G-code), Smirnov 2019, §3.4;
//  - `spin` on six-axis machines: the turn s about the tool axis, R = R_axis · Rot(a', s), where R_axis is
//  the
//    shortest swing of the home rotation that puts the tool axis a' (platform frame) where the program wants
//    it. For a vertical tool and an upright home, s is the G-code C angle (a milling spindle does not care,
//    ch3 (89));
//  - `all` on six-axis machines: the three angles of the machine's own convention (a ball-end mill only needs
//    the sphere centre, ch3 (90)–(93)); absolute values, as the machine file states its poses.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/pose.hpp"
#include "core/result.hpp"
#include "machine/mechanism.hpp"

namespace pkm::redundancy {

enum class FreeSet { spin, all };
std::optional<FreeSet> free_set_from_string(std::string_view name);
std::string_view to_string(FreeSet set);

/// Values of the free coordinates in radians; only the first FreeCoordinates::count() are used.
using FreeValues = Eigen::Vector3d;

/// Bounds of the free coordinates, degrees (absolute values): none (each may move ±30° from its start), one
/// [lo, hi] for every coordinate, or one per coordinate in order.
using FreeBounds = std::vector<std::array<double, 2>>;

/// What the program fixes at one point of the tool path, in the machine's base frame.
struct PathPoint {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();  ///< tool point
  /// The rotation that puts the tool axis where the program wants it, spin at the reference (R_axis above).
  Eigen::Matrix3d axis_rotation = Eigen::Matrix3d::Identity();
  /// The rotation the program itself gives here (its spin included), as the planner moves: for analyses that
  /// take the program as it is (pkm stiffness).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d tangent = Eigen::Vector3d::Zero();  ///< unit direction of travel into this point (0: none)
  double step_mm = 0.0;                               ///< tool-point path length from the previous point
  int line = 0;                                       ///< source line of the move this point belongs to
  int move_index = -1;   ///< index of that move in the program (-1: the start point)
  bool cutting = false;  ///< a feed move (cutting loads apply), not a rapid
  /// The move's programmed feed, mm/s (0 on rapids): the tool's speed along the step under the dynamic force
  /// model (LawOptions::forces).
  double feed_mm_s = 0.0;
};

class FreeCoordinates {
 public:
  enum class Kind { planar_angle, spin, convention_angles };

  /// `bounds_deg`: see FreeBounds; errors name a range that is empty or excludes the start, or a count that
  /// is neither one nor the coordinates'.
  static Result<FreeCoordinates> create(const Mechanism& mechanism, FreeSet set, const FreeBounds& bounds_deg,
                                        const FreeValues& start_rad);

  Kind kind() const { return kind_; }
  int count() const { return count_; }
  std::string name(int i) const;
  double lower_rad(int i) const { return lower_rad_[i]; }
  double upper_rad(int i) const { return upper_rad_[i]; }
  const FreeValues& start() const { return start_; }
  /// Clamps values into the bounds.
  FreeValues clamp(const FreeValues& values) const;

  /// The pose at a path point with the free coordinates set to `values` (hot path: no allocation).
  Pose pose(const PathPoint& point, const FreeValues& values) const noexcept;
  /// The free-coordinate values of a platform rotation at a path point (inverse of pose() in the angles).
  FreeValues values_of(const Eigen::Matrix3d& rotation, const PathPoint& point) const;

  /// Start values of a kind for `rotation` at `point`, before bounds exist (used to build the object).
  static FreeValues values_for(Kind kind, AngleConvention convention,
                               const Eigen::Vector3d& tool_axis_platform, const Eigen::Matrix3d& rotation,
                               const PathPoint& point);
  static Result<Kind> kind_for(const Mechanism& mechanism, FreeSet set);

 private:
  Kind kind_ = Kind::planar_angle;
  int count_ = 1;
  AngleConvention convention_ = AngleConvention::abc;
  Eigen::Vector3d tool_axis_platform_ = Eigen::Vector3d::UnitZ();
  FreeValues start_ = FreeValues::Zero();
  std::array<double, 3> lower_rad_{};
  std::array<double, 3> upper_rad_{};
};

}  // namespace pkm::redundancy
