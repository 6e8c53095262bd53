// All assembly modes of the planar 3-RPR platform by elimination to one trigonometric polynomial in φ.
//
// With c_j(φ) = R(φ) b'_j − A_j, the squared eq. (8) reads |C|² + 2 C·c_j + |c_j|² − L_j² = 0. The
// differences of equations 2 and 3 from equation 1 are linear in C for fixed φ: M(φ) C = r(φ), with rows
// 2(c_j − c_1)ᵀ and r_j = (L_j² − L_1²) − (|c_j|² − |c_1|²). Substituting C = adj(M) r / det M into
// equation 1 and multiplying by det² M gives
//   G(φ) = |adj(M) r|² + 2 det M (adj(M) r)·c_1 + det² M (|c_1|² − L_1²),
// whose every real root is a candidate φ. The terms reach harmonic 5, but the harmonics above 3 cancel
// (checked on random layouts; it is the classical sextic of the 3-RPR), so G has degree 3: at most 6 roots
// on [0, 2π), six assembly modes. G has no division, so it stays valid where det M = 0: there
// G = |adj(M) r|², which vanishes exactly where M C = r is solvable.
//
// G is sampled at 32 equispaced angles (harmonics up to 15 resolved, so the degree is measured, not
// assumed); its Fourier coefficients g_k give P(z) = z^n Σ g_k z^k, z = e^{iφ}, whose roots come from a
// companion matrix. Roots near |z| = 1 give φ. C comes from adj(M) r / det M and, because det M can vanish at
// a solution (congruent base and platform triangles at φ = 0, or A_j = R(φ*) b'_j + s_j w), also from the
// circle–circle intersections of every pair of struts. Every candidate is polished by Newton
// (Planar3::solve_from); those that converge within the tolerance are kept, duplicates removed, nearest to
// home first.
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <optional>

#include "core/units.hpp"
#include "machine/planar3.hpp"
#include "machine/solution_set.hpp"

namespace pkm {
namespace {

constexpr int kSamples = 32;  ///< samples of G per turn: resolves harmonics up to 15 (G has degree 3)
/// Fourier coefficients below this fraction of the largest are rounding noise of the cancelled harmonics.
constexpr double kCoefficientFloor = 1e-10;
/// G counts as identically zero (a continuum of assembly modes) below this fraction of its terms' magnitude.
constexpr double kIdenticallyZero = 1e-12;
/// Roots of P(z) with ||z| − 1| up to this are tried as real φ (a double root splits off the circle by about
/// √ε; a spurious candidate only costs a Newton run that does not converge).
constexpr double kUnitCircleBand = 0.02;
/// Below this |det M| (scaled units) C is not taken from adj(M) r / det M; the circle pairs cover that case.
constexpr double kMinEliminationDeterminant = 1e-9;

struct Elimination {
  Eigen::Matrix2d adjugate;
  double determinant;
  Eigen::Vector2d adj_r;
  Eigen::Vector2d c1;
  double g;          ///< G(φ)
  double magnitude;  ///< sum of |terms| of G, for the identically-zero test
};

/// Data in units of a characteristic length, so that G is of order one whatever the machine's size.
struct ScaledProblem {
  std::array<Eigen::Vector2d, 3> a, b;
  std::array<double, 3> l;

  Eigen::Vector2d c(int j, double phi) const {
    const double cs = std::cos(phi), sn = std::sin(phi);
    return Eigen::Vector2d(cs * b[j].x() - sn * b[j].y(), sn * b[j].x() + cs * b[j].y()) - a[j];
  }

  Elimination eliminate(double phi) const {
    std::array<Eigen::Vector2d, 3> cj = {c(0, phi), c(1, phi), c(2, phi)};
    Eigen::Matrix2d m;
    Eigen::Vector2d r;
    for (int k = 0; k < 2; ++k) {
      m.row(k) = 2.0 * (cj[k + 1] - cj[0]).transpose();
      r[k] = (l[k + 1] * l[k + 1] - l[0] * l[0]) - (cj[k + 1].squaredNorm() - cj[0].squaredNorm());
    }
    Elimination e;
    e.adjugate << m(1, 1), -m(0, 1), -m(1, 0), m(0, 0);
    e.determinant = m.determinant();
    e.adj_r = e.adjugate * r;
    e.c1 = cj[0];
    const double t1 = e.adj_r.squaredNorm();
    const double t2 = 2.0 * e.determinant * e.adj_r.dot(cj[0]);
    const double t3 = e.determinant * e.determinant * (cj[0].squaredNorm() - l[0] * l[0]);
    e.g = t1 + t2 + t3;
    e.magnitude = std::abs(t1) + std::abs(t2) + std::abs(t3);
    return e;
  }
};

/// Real roots φ of the trigonometric polynomial with coefficients g_0..g_n (g_{−k} = conj g_k).
std::vector<double> unit_circle_roots(const std::vector<std::complex<double>>& g, int n) {
  // P(z) = Σ_{m=0}^{2n} p_m z^m with p_m = g_{m−n}; companion matrix of the monic P / p_{2n}.
  const int degree = 2 * n;
  std::vector<std::complex<double>> p(degree + 1);
  for (int m = 0; m <= degree; ++m) {
    const int k = m - n;
    p[m] = k >= 0 ? g[k] : std::conj(g[-k]);
  }
  Eigen::MatrixXcd companion = Eigen::MatrixXcd::Zero(degree, degree);
  for (int i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
  for (int i = 0; i < degree; ++i) companion(i, degree - 1) = -p[i] / p[degree];
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> solver(companion, false);
  std::vector<double> roots;
  for (int i = 0; i < degree; ++i) {
    const std::complex<double> z = solver.eigenvalues()[i];
    if (std::abs(std::abs(z) - 1.0) <= kUnitCircleBand) roots.push_back(std::arg(z));
  }
  return roots;
}

/// Points at distance `ra` from `a` and `rb` from `b` (0, 1 or 2 of them).
void circle_circle(const Eigen::Vector2d& a, double ra, const Eigen::Vector2d& b, double rb,
                   std::vector<Eigen::Vector2d>& out) {
  const Eigen::Vector2d ab = b - a;
  const double d = ab.norm();
  if (!(d > 1e-12)) return;
  const double along = (ra * ra - rb * rb + d * d) / (2.0 * d);
  const double h2 = ra * ra - along * along;
  if (h2 < -1e-9 * ra * ra) return;
  const Eigen::Vector2d u = ab / d, n(-u.y(), u.x());
  const double h = std::sqrt(std::fmax(h2, 0.0));
  out.push_back(a + along * u + h * n);
  out.push_back(a + along * u - h * n);
}

/// The problem in units of the largest of the lengths and joint radii (mm); returns that length.
double scale_problem(const Planar3Geometry& geometry, const ActuatorVector& q, ScaledProblem& problem) {
  double scale_mm = q.maxCoeff();
  for (int j = 0; j < 3; ++j) {
    scale_mm = std::fmax(scale_mm, geometry.base_joints_mm[j].norm());
    scale_mm = std::fmax(scale_mm, geometry.platform_joints_mm[j].norm());
  }
  for (int j = 0; j < 3; ++j) {
    problem.a[j] = geometry.base_joints_mm[j] / scale_mm;
    problem.b[j] = geometry.platform_joints_mm[j] / scale_mm;
    problem.l[j] = q[j] / scale_mm;
  }
  return scale_mm;
}

/// Candidate angles φ (rad): the real roots of G. Empty optional when G vanishes identically.
std::optional<std::vector<double>> candidate_angles(const ScaledProblem& problem) {
  std::array<double, kSamples> samples{};
  double magnitude = 0.0;
  for (int s = 0; s < kSamples; ++s) {
    const Elimination e = problem.eliminate(2.0 * kPi * s / kSamples);
    samples[s] = e.g;
    magnitude = std::fmax(magnitude, e.magnitude);
  }
  // Fourier coefficients g_0 .. g_{N/2−1} of G from its samples.
  std::vector<std::complex<double>> g(kSamples / 2);
  double largest = 0.0;
  for (int k = 0; k < kSamples / 2; ++k) {
    for (int s = 0; s < kSamples; ++s)
      g[k] += samples[s] * std::polar(1.0 / kSamples, -2.0 * kPi * k * s / kSamples);
    largest = std::fmax(largest, std::abs(g[k]));
  }
  if (!(largest > kIdenticallyZero * magnitude)) return std::nullopt;
  int n = 0;
  for (int k = 0; k < kSamples / 2; ++k) {
    if (std::abs(g[k]) > kCoefficientFloor * largest) n = k;
  }
  return n > 0 ? unit_circle_roots(g, n) : std::vector<double>{};
}

/// Candidate tool points (scaled units) for one φ: from the elimination and from every pair of struts.
std::vector<Eigen::Vector2d> candidate_centres(const ScaledProblem& problem, double phi) {
  std::vector<Eigen::Vector2d> centres;
  const Elimination e = problem.eliminate(phi);
  if (std::abs(e.determinant) > kMinEliminationDeterminant) centres.push_back(e.adj_r / e.determinant);
  for (int j = 0; j < 3; ++j) {
    const int k = (j + 1) % 3;
    circle_circle(-problem.c(j, phi), problem.l[j], -problem.c(k, phi), problem.l[k], centres);
  }
  return centres;
}

}  // namespace

Result<std::vector<FkSolution>> Planar3::forward_all(const ActuatorVector& q,
                                                     const FkOptions& options) const {
  if (q.size() != 3) {
    return make_error(ErrorCode::bad_input, fmt::format("planar3 needs 3 strut lengths, got {}", q.size()));
  }
  if (!(q.minCoeff() > 0.0)) {
    return make_error(ErrorCode::unreachable,
                      fmt::format("strut lengths must be positive: L = ({:.6f}, {:.6f}, "
                                  "{:.6f}) mm",
                                  q[0], q[1], q[2]));
  }
  ScaledProblem problem;
  const double scale_mm = scale_problem(geometry_, q, problem);
  const auto angles = candidate_angles(problem);
  if (!angles) {
    return make_error(
        ErrorCode::singular,
        fmt::format("strut lengths ({:.6f}, {:.6f}, {:.6f}) mm admit a continuum of platform poses "
                    "(architecture singularity)",
                    q[0], q[1], q[2]));
  }

  std::vector<FkSolution> solutions;
  bool singular_seen = false;
  FkOptions polish = options;
  polish.require_same_branch = false;
  for (double phi : *angles) {
    for (const Eigen::Vector2d& centre : candidate_centres(problem, phi)) {
      const Eigen::Vector3d start(centre.x() * scale_mm, centre.y() * scale_mm, phi);
      auto polished = solve_from(q, start, polish);
      if (!polished) {
        singular_seen = singular_seen || polished.error().code == ErrorCode::singular;
        continue;
      }
      if (contains_solution(solutions, polished->pose)) continue;
      polished->branch = branch_of(planar_coordinates(polished->pose));
      solutions.push_back(*polished);
    }
  }
  if (solutions.empty()) {
    if (singular_seen) {
      return make_error(
          ErrorCode::singular,
          fmt::format("strut lengths ({:.6f}, {:.6f}, {:.6f}) mm fit the platform only in a singular "
                      "configuration",
                      q[0], q[1], q[2]));
    }
    return make_error(
        ErrorCode::unreachable,
        fmt::format("no assembly of the platform fits strut lengths ({:.6f}, {:.6f}, {:.6f}) mm", q[0], q[1],
                    q[2]));
  }
  // Nearest to home first; a rotation is weighed by the platform radius (about the distance its joints move).
  sort_nearest_to(solutions, home_, platform_radius_mm_);
  return solutions;
}

}  // namespace pkm
