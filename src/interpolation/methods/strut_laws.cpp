#include "interpolation/methods/strut_laws.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "interpolation/methods/law_fit.hpp"

namespace pkm::interpolation {

std::string_view to_string(LawModel model) {
  switch (model) {
    case LawModel::exact:
      return "exact";
    case LawModel::sqrt_quadratic:
      return "sqrt_quadratic";
    case LawModel::sqrt_fourier:
      return "sqrt_fourier";
    case LawModel::polynomial:
      return "polynomial";
  }
  return "?";
}

namespace {

// Nodes of the least-squares fits of the 3-coefficient sqrt models: more than 3, so that the fit averages
// round-off instead of interpolating it.
constexpr int kLawFitSqrtNodes = 8;
// A move counts as keeping its orientation (and a helix as flat, of constant radius) below these: the closed
// models are then tried, and the fit-error check decides whether they hold.
constexpr double kLawFitConstantRotationRad = 1e-12;
constexpr double kLawFitFlatArcMm = 1e-6;
constexpr int kLawFitMaxDegree = 12;  // monomials in u ∈ [−1, 1] stay well conditioned up to here

Pose law_fit_pose(const path::PathPoint& point) {
  return Pose{point.position_mm, point.rotation.toRotationMatrix()};
}

Status law_fit_check_settings(const LawFitSettings& settings) {
  if (!(settings.tolerance > 0.0) || !std::isfinite(settings.tolerance))
    return make_error(ErrorCode::bad_input,
                      fmt::format("strut-law tolerance must be positive, got {}", settings.tolerance));
  if (settings.polynomial_degree < 1 || settings.polynomial_degree > kLawFitMaxDegree)
    return make_error(ErrorCode::bad_input, fmt::format("strut-law polynomial degree must be 1 to {}, got {}",
                                                        kLawFitMaxDegree, settings.polynomial_degree));
  if (settings.check_points < 1)
    return make_error(ErrorCode::bad_input, fmt::format("strut-law check points must be at least 1, got {}",
                                                        settings.check_points));
  if (!(settings.min_piece_length > 0.0))
    return make_error(
        ErrorCode::bad_input,
        fmt::format("strut-law minimum piece length must be positive, got {}", settings.min_piece_length));
  return ok_status();
}

}  // namespace

/// Fits the laws segment by segment (a friend of StrutLaws: it fills the pieces and the coefficient table).
class StrutLawBuilder {
 public:
  StrutLawBuilder(StrutLaws& laws, const LawFitSettings& settings, const std::string& source)
      : laws_(laws),
        path_(*laws.path_),
        mechanism_(*laws.machine_->mechanism),
        settings_(settings),
        source_(source),
        polynomial_nodes_(law_fit_lobatto_nodes(settings.polynomial_degree + 1)),
        sqrt_nodes_(law_fit_chebyshev_nodes(kLawFitSqrtNodes)) {
    closed_models_ = mechanism_.has_distance_actuators();
  }

  Status fit_segment(int index) {
    const path::Segment& segment = path_.segment(index);
    return fit_range(index, segment.s_start, segment.s_start + segment.length, model_for(segment));
  }

 private:
  /// IK at s on segment `index`; errors name the source line.
  Status sample(int index, double s, double* values) const {
    const path::Segment& segment = path_.segment(index);
    auto ik = mechanism_.inverse(law_fit_pose(path_.evaluate(index, s)));
    if (!ik) {
      return make_error(ik.error().code,
                        fmt::format("{}:{}: strut law: the path leaves the workspace at s = {}: {}", source_,
                                    segment.line, s, ik.error().message));
    }
    for (int j = 0; j < laws_.actuators_; ++j) values[j] = (*ik)[j];
    return ok_status();
  }

  /// The closed models of §5.2.2 suit only strut machines (L = |C + R·b' − A|) on lines and flat arcs at
  /// constant orientation; everything else gets the polynomial.
  LawModel model_for(const path::Segment& segment) const {
    if (!closed_models_ || segment.is_blend() || segment.rotation_only || !(segment.length > 0.0))
      return LawModel::polynomial;
    const path::Curve& curve = path_.curve(segment.curve_a);
    if (curve.rotation_angle_rad > kLawFitConstantRotationRad) return LawModel::polynomial;
    if (curve.kind == path::CurveKind::line) return LawModel::sqrt_quadratic;
    if (std::abs(curve.axial_mm) <= kLawFitFlatArcMm &&
        std::abs(curve.radius_end_mm - curve.radius_mm) <= kLawFitFlatArcMm)
      return LawModel::sqrt_fourier;
    return LawModel::polynomial;
  }

  LawPiece make_piece(int index, double s0, double s1, LawModel model) const {
    const path::Segment& segment = path_.segment(index);
    LawPiece piece;
    piece.s_start = s0;
    piece.s_end = s1;
    piece.s_mid = 0.5 * (s0 + s1);
    piece.u_per_s = s1 > s0 ? 2.0 / (s1 - s0) : 0.0;
    piece.model = s1 > s0 ? model : LawModel::polynomial;  // a piece of zero length: a constant
    piece.segment = index;
    piece.line = segment.line;
    piece.stride = piece.model == LawModel::polynomial ? (s1 > s0 ? settings_.polynomial_degree + 1 : 1) : 3;
    if (piece.model == LawModel::sqrt_fourier) {
      // The arc angle is linear in s: the segment's share of the curve's sweep over its length.
      const path::Curve& curve = path_.curve(segment.curve_a);
      const double angle_per_s = curve.sweep_rad * (segment.fa1 - segment.fa0) / segment.length;
      piece.angle_per_u = angle_per_s / piece.u_per_s;
    }
    return piece;
  }

  /// Fits `model` on [s0, s1] of segment `index`, checks it, and falls back or splits (see strut_laws.hpp).
  Status fit_range(int index, double s0, double s1, LawModel model) {
    LawPiece piece = make_piece(index, s0, s1, model);
    const std::size_t mark = laws_.coefficients_.size();
    if (Status s = fit_coefficients(piece); !s) return s;
    auto error = measure(piece);
    if (!error) return error.error();
    piece.fit_error = *error;
    const bool splittable = 0.5 * (s1 - s0) >= settings_.min_piece_length;
    if (*error <= settings_.tolerance || (piece.model == LawModel::polynomial && !splittable)) {
      laws_.pieces_.push_back(piece);
      return ok_status();
    }
    laws_.coefficients_.resize(mark);
    if (piece.model != LawModel::polynomial) return fit_range(index, s0, s1, LawModel::polynomial);
    const double middle = 0.5 * (s0 + s1);
    if (Status s = fit_range(index, s0, middle, LawModel::polynomial); !s) return s;
    return fit_range(index, middle, s1, LawModel::polynomial);
  }

  /// IK at the piece's nodes, the least-squares fit, and the coefficients appended to the table. The
  /// polynomial interpolates IK at Chebyshev–Lobatto nodes, ends included: neighbouring pieces then join
  /// without a step, and the drives see none at a piece boundary.
  Status fit_coefficients(LawPiece& piece) {
    const int actuators = laws_.actuators_;
    const Eigen::VectorXd u = piece.model != LawModel::polynomial ? sqrt_nodes_
                              : piece.stride == 1                 ? law_fit_lobatto_nodes(1)
                                                                  : polynomial_nodes_;
    Eigen::MatrixXd values(u.size(), actuators);
    std::array<double, kMaxActuators> q{};
    for (Eigen::Index i = 0; i < u.size(); ++i) {
      const double s = piece.u_per_s > 0.0 ? piece.s_mid + u[i] / piece.u_per_s : piece.s_mid;
      if (Status st = sample(piece.segment, s, q.data()); !st) return st;
      for (int j = 0; j < actuators; ++j) values(i, j) = q[j];
    }
    const Eigen::MatrixXd c = law_fit_coefficients(piece.model, u, piece.angle_per_u, piece.stride, values);
    piece.offset = static_cast<int>(laws_.coefficients_.size());
    for (int j = 0; j < actuators; ++j)
      for (int k = 0; k < piece.stride; ++k) laws_.coefficients_.push_back(c(k, j));
    return ok_status();
  }

  /// Largest |fitted − IK| at the middles of `check_points` equal parts of the piece: inside it and none of
  /// them a fit node (with the default 32 they are odd multiples of 1/32 in u, the nodes cos(kπ/d) and
  /// cos((2k + 1)π/16) are not).
  Result<double> measure(const LawPiece& piece) const {
    const int actuators = laws_.actuators_;
    const int count = settings_.check_points;
    std::array<double, kMaxActuators> exact{}, fitted{};
    double worst = 0.0;
    for (int k = 0; k < count; ++k) {
      const double s = piece.s_start + (piece.s_end - piece.s_start) * (k + 0.5) / count;
      if (Status st = sample(piece.segment, s, exact.data()); !st) return st.error();
      evaluate_fitted_piece(piece, laws_.coefficients_.data() + piece.offset, actuators, s, fitted.data());
      for (int j = 0; j < actuators; ++j) {
        const double e = std::abs(fitted[j] - exact[j]);
        if (!(e <= worst)) worst = std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
      }
    }
    return worst;
  }

  StrutLaws& laws_;
  const path::Path& path_;
  const Mechanism& mechanism_;
  const LawFitSettings& settings_;
  const std::string& source_;
  Eigen::VectorXd polynomial_nodes_;
  Eigen::VectorXd sqrt_nodes_;
  bool closed_models_ = false;
};

StrutLaws::StrutLaws(const Machine& machine, const path::Path& path)
    : machine_(&machine),
      path_(&path),
      actuators_(machine.mechanism->actuator_count()),
      length_(path.length()) {}

// Nothing is solved here, so nothing fails: an unreachable pose shows as a false evaluate().
Result<StrutLaws> StrutLaws::exact(const Machine& machine, const path::Path& path,
                                   const std::string& /*source*/) {
  StrutLaws laws(machine, path);
  laws.exact_ = true;
  laws.pieces_.reserve(path.segments.size());
  for (int k = 0; k < static_cast<int>(path.segments.size()); ++k) laws.append_exact_piece(k);
  return laws;
}

Result<StrutLaws> StrutLaws::fit(const Machine& machine, const path::Path& path,
                                 const LawFitSettings& settings, const std::string& source) {
  if (Status s = law_fit_check_settings(settings); !s) return s.error();
  StrutLaws laws(machine, path);
  laws.exact_ = false;
  laws.settings_ = settings;
  laws.source_ = source;
  if (Status fitted = laws.fit_through(static_cast<int>(path.segments.size())); !fitted)
    return fitted.error();
  if (path.segments.empty()) {
    if (Status started = laws.take_start_values(); !started) return started.error();
  }
  return laws;
}

Result<StrutLaws> StrutLaws::window(const Machine& machine, const path::Path& path,
                                    const std::optional<LawFitSettings>& settings,
                                    const std::string& source) {
  if (settings) {
    if (Status s = law_fit_check_settings(*settings); !s) return s.error();
  }
  StrutLaws laws(machine, path);
  laws.exact_ = !settings;
  if (settings) laws.settings_ = *settings;
  laws.source_ = source;
  laws.finished_ = false;
  laws.length_ = 0.0;
  return laws;
}

Status StrutLaws::fit_through(int segment_end) {
  if (exact_) {
    for (; fitted_end_ < segment_end; ++fitted_end_) append_exact_piece(fitted_end_);
  } else if (fitted_end_ < segment_end) {
    StrutLawBuilder builder(*this, settings_, source_);
    for (; fitted_end_ < segment_end; ++fitted_end_) {
      const std::size_t first = pieces_.size();
      if (Status s = builder.fit_segment(fitted_end_); !s) return s;
      for (std::size_t p = first; p < pieces_.size(); ++p) account(pieces_[p]);
    }
  }
  if (!finished_ && fitted_end_ > 0) {
    const path::Segment& last = path_->segment(fitted_end_ - 1);
    length_ = last.s_start + last.length;
  }
  return ok_status();
}

Status StrutLaws::finish() {
  if (Status fitted = fit_through(path_->segment_end()); !fitted) return fitted;
  finished_ = true;
  length_ = path_->length();
  if (fitted_end_ == 0 && !exact_) return take_start_values();
  return ok_status();
}

void StrutLaws::drop_before(int segment) {
  std::size_t drop = 0;
  while (drop + 1 < pieces_.size() && pieces_[drop + 1].segment < segment) ++drop;
  if (drop == 0 || 2 * drop < pieces_.size()) return;
  const std::size_t coefficients = static_cast<std::size_t>(pieces_[drop].offset);
  pieces_.erase(pieces_.begin(), pieces_.begin() + static_cast<std::ptrdiff_t>(drop));
  piece_base_ += static_cast<int>(drop);
  coefficients_.erase(coefficients_.begin(),
                      coefficients_.begin() + static_cast<std::ptrdiff_t>(coefficients));
  for (LawPiece& piece : pieces_) piece.offset -= static_cast<int>(coefficients);
}

void StrutLaws::append_exact_piece(int index) {
  const path::Segment& segment = path_->segment(index);
  LawPiece piece;
  piece.s_start = segment.s_start;
  piece.s_end = segment.s_start + segment.length;
  piece.s_mid = 0.5 * (piece.s_start + piece.s_end);
  piece.model = LawModel::exact;
  piece.segment = index;
  piece.line = segment.line;
  pieces_.push_back(piece);
  account(piece);
}

Status StrutLaws::take_start_values() {
  auto ik = machine_->mechanism->inverse(law_fit_pose(path_->start));
  if (!ik) {
    return make_error(ik.error().code, fmt::format("{}: strut law: the path's start is out of reach: {}",
                                                   source_, ik.error().message));
  }
  for (int j = 0; j < actuators_; ++j) start_values_[j] = (*ik)[j];
  return ok_status();
}

// The report counts every piece ever fitted, also those a window has forgotten since.
void StrutLaws::account(const LawPiece& piece) {
  LawReport& report = report_;
  switch (piece.model) {
    case LawModel::exact:
      ++report.exact;
      break;
    case LawModel::sqrt_quadratic:
      ++report.sqrt_quadratic;
      break;
    case LawModel::sqrt_fourier:
      ++report.sqrt_fourier;
      break;
    case LawModel::polynomial:
      ++report.polynomial;
      break;
  }
  // Exact pieces have no fit error (and no line of the largest one, as the whole exact laws report).
  if (piece.model != LawModel::exact && (report.pieces == 0 || piece.fit_error > report.max_fit_error)) {
    report.max_fit_error = piece.fit_error;
    report.max_fit_error_line = piece.line;
  }
  ++report.pieces;
}

int StrutLaws::find_piece(double s, int hint) const noexcept {
  const int n = static_cast<int>(pieces_.size());
  if (n == 0) return piece_base_;
  int i = std::clamp(hint - piece_base_, 0, n - 1);
  if (s >= pieces_[i].s_start) {
    // Monotone use moves at most a piece or two per call; a long jump falls through to the binary search.
    for (int step = 0; step < 4; ++step) {
      if (i + 1 == n || s < pieces_[i + 1].s_start) return piece_base_ + i;
      ++i;
    }
  }
  const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), s,
                                   [](double value, const LawPiece& piece) { return value < piece.s_start; });
  return piece_base_ + std::max(0, static_cast<int>(it - pieces_.begin()) - 1);
}

bool StrutLaws::solve_inverse(const path::PathPoint& point, double* actuators) const noexcept {
  const Pose pose = law_fit_pose(point);
  return machine_->mechanism->actuator_values(pose, actuators);
}

bool StrutLaws::evaluate(double s, int& hint, double* actuators) const noexcept {
  if (!(s > 0.0)) s = 0.0;  // also NaN
  if (s > length_) s = length_;
  if (pieces_.empty()) {
    if (exact_) return solve_inverse(path_->start, actuators);
    std::copy_n(start_values_.begin(), actuators_, actuators);
    return true;
  }
  hint = find_piece(s, hint);
  const LawPiece& piece = pieces_[hint - piece_base_];
  if (piece.model == LawModel::exact) return solve_inverse(path_->evaluate(piece.segment, s), actuators);
  evaluate_fitted_piece(piece, coefficients_.data() + piece.offset, actuators_, s, actuators);
  return true;
}

}  // namespace pkm::interpolation
