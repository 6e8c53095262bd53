#pragma once
// Analytic strut laws L_j(s) along a planned tool path (Smirnov 2019, §5.2.2): every actuator's value as a
// cheap closed function of the path parameter s (mm of tool travel; degrees along moves that only rotate),
// so that an interpolator running at the carrier frequency composes it with its own timing law s(τ) and
// never solves inverse kinematics in its period. The laws are fitted per path segment to inverse-kinematics
// samples, with the model chosen by the segment's kind:
//   - a straight line at constant orientation: L² is exactly quadratic in s for a strut machine
//     (L = |C(s) + R·b'_j − A_j|, C linear in s): sqrt-quadratic, eq. 149;
//   - a circular arc at constant orientation: L² = a0 + a1 cos θ + b1 sin θ with θ linear in s:
//     sqrt-Fourier, eqs. 148/150;
//   - anything else (changing orientation, blends, helices, and every segment of a mechanism that is not a
//     hexapod, whose actuators are no such distances): a polynomial of degree 6, eq. 151.
// The fit error is then measured against exact IK at check points inside the piece (not the fit nodes).
// A closed model that misses the tolerance falls back to the polynomial; a polynomial that misses it is
// split in halves, recursively, down to a minimum piece length, where a remaining error is kept and reported
// (LawReport), not refused. The tolerance defaults to 10 % of the strut budget of eq. 155 (§5.2.2).
//
// Along a plan made while it streams, the laws are a window too: segments are fitted once the plan has passed
// them (they no longer change) and forgotten behind the interpolator, piece for piece as the whole path's.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "interpolation/methods/strut_law_piece.hpp"
#include "machine/machine.hpp"
#include "path/path.hpp"

namespace pkm {}

namespace pkm::interpolation {

struct LawFitSettings {
  double tolerance = 9e-6;  ///< largest |fitted − IK| actuator value (mm; rad for angular actuators): 10 % of
                            ///< ΔL_allowed = 0.9·ρ_max/δρ_max for ρ_max = 1 µm, δρ_max = 10 (§5.2.2)
  int polynomial_degree = 6;  ///< eq. 151
  int check_points = 32;      ///< per piece, where the fit error is measured against IK (not the fit nodes)
  double min_piece_length = 1e-3;  ///< path units; pieces are not split below this
};

struct LawReport {
  int pieces = 0;
  int exact = 0, sqrt_quadratic = 0, sqrt_fourier = 0, polynomial = 0;  ///< pieces per model
  double max_fit_error = 0.0;  ///< largest measured |fitted − IK| over all check points
  int max_fit_error_line = 0;  ///< program line of the piece where it occurs
};

/// The laws keep pointers to the machine and the path they were made for: the caller keeps both alive (and
/// in place) for as long as the laws are used.
class StrutLaws {
 public:
  /// No fit: every evaluation solves IK (the reference). Pieces = path segments.
  static Result<StrutLaws> exact(const Machine& machine, const path::Path& path, const std::string& source);
  /// Fitted per path segment (§5.2.2). Errors (IK failing at a sample) name `source`:line of the segment.
  static Result<StrutLaws> fit(const Machine& machine, const path::Path& path, const LawFitSettings& settings,
                               const std::string& source);

  /// Laws over a path still growing (a streamed plan's window): nothing fitted yet. Fitted with `settings`,
  /// or exact (IK at every evaluation) without.
  static Result<StrutLaws> window(const Machine& machine, const path::Path& path,
                                  const std::optional<LawFitSettings>& settings, const std::string& source);
  /// Fits the segments not fitted yet before `segment_end` (whole-path index); they must be final.
  Status fit_through(int segment_end);
  /// The path is whole: fits the rest; length() is then the path's.
  Status finish();
  /// One past the last segment fitted.
  int fitted_end() const { return fitted_end_; }
  /// The pieces held (a window's, or all).
  std::size_t held_pieces() const { return pieces_.size(); }
  /// Forgets the pieces of the segments before `segment` (amortised O(1)); their report stays.
  void drop_before(int segment);

  int actuator_count() const { return actuators_; }
  double length() const { return length_; }  ///< the path's length (a window's: as far as it is fitted)
  /// Actuator values at path parameter s (clamped to [0, length()]); `hint` is a piece index, updated
  /// (monotone use is O(1), any s works). False only when IK fails (exact model). No allocation.
  bool evaluate(double s, int& hint, double* actuators) const noexcept;
  /// One past the last piece's index (pieces are numbered along the whole path, also in a window).
  int piece_count() const { return piece_base_ + static_cast<int>(pieces_.size()); }
  LawModel model(int piece) const { return pieces_[piece - piece_base_].model; }
  int line(int piece) const { return pieces_[piece - piece_base_].line; }  ///< the piece's source line
  const LawReport& report() const { return report_; }

  /// The whole piece: its span of s, segment, local variable and measured fit error.
  const LawPiece& piece(int index) const { return pieces_[index - piece_base_]; }
  /// Actuator `actuator`'s coefficients on `piece` in the piece's basis (strut_law_piece.hpp); empty for
  /// exact pieces.
  std::span<const double> coefficients(int piece, int actuator) const {
    const LawPiece& p = pieces_[piece - piece_base_];
    return {coefficients_.data() + p.offset + static_cast<std::size_t>(p.stride) * actuator,
            static_cast<std::size_t>(p.stride)};
  }
  /// The piece containing s, searching from `hint` (forward steps for monotone use, else a binary search).
  int find_piece(double s, int hint) const noexcept;

 private:
  friend class StrutLawBuilder;
  StrutLaws(const Machine& machine, const path::Path& path);
  bool solve_inverse(const path::PathPoint& point, double* actuators) const noexcept;
  void append_exact_piece(int segment);
  Status take_start_values();
  void account(const LawPiece& piece);

  const Machine* machine_ = nullptr;
  const path::Path* path_ = nullptr;
  int actuators_ = 0;
  double length_ = 0.0;
  bool exact_ = true;
  std::vector<LawPiece> pieces_;      ///< from piece piece_base_ on
  std::vector<double> coefficients_;  ///< the pieces' offsets index this table
  int piece_base_ = 0;
  int fitted_end_ = 0;  ///< segments fitted: [0, fitted_end_)
  bool finished_ = true;
  LawFitSettings settings_;
  std::string source_;
  std::array<double, kMaxActuators> start_values_{};  ///< fitted laws of a path without segments
  LawReport report_;
};

}  // namespace pkm::interpolation
