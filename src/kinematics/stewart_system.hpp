#pragma once
// The forward kinematics of a general 6-6 Gough–Stewart platform as polynomials in Study coordinates, over
// the complex numbers, for path tracking (kinematics/stewart_homotopy.hpp).
//
// A pose is a pair of quaternions x = (e, g): e the rotation (unnormalised), g its dual part, with
//   rotation R = e·(·)·e*/|e|²,   position p = 2·g·e*/|e|²,   Study quadric  eᵀg = 0,
// where |·|² and ᵀ are the bilinear (not Hermitian) forms, so that the equations stay polynomial over ℂ. With
// A_j the base joints, b_j the platform joints (platform frame), the leg p + R·b_j − A_j equals
// (2g + e·b_j − A_j·e)·e*/|e|², so |leg|² = L_j² becomes a quadric in (e, g):
//   f_j = 4 gᵀg + 4 gᵀy_j + y_jᵀy_j − L_j² eᵀe = 0,   y_j = e·b_j − A_j·e = M_j e,
//   M_j e = ( d_j·e_v ,  e_0 (−d_j) + e_v × s_j ),   d_j = A_j − b_j,  s_j = A_j + b_j.
// With the Study quadric and a random complex chart cᵀe = 1 (which fixes the scale of (e, g) and puts
// no real pose at infinity), these are 8 equations in 8 unknowns with 40 isolated solutions for generic
// parameters (Wampler 1996, "Forward displacement analysis of general six-in-parallel SPS platform
// manipulators using soma coordinates"). Everything here is fixed-size: nothing allocates.
#include <Eigen/Core>
#include <array>
#include <complex>

#include "kinematics/complex_lu.hpp"

namespace pkm {

using Complex = std::complex<double>;
using StudyPoint = Eigen::Matrix<Complex, 8, 1>;  ///< (e0, e1, e2, e3, g0, g1, g2, g3)
using StudyJacobian = Eigen::Matrix<Complex, 8, 8>;

/// The parameters of one instance: base joints, platform joints (platform frame), squared leg lengths. They
/// enter the equations only as d_j = A_j − b_j, s_j = A_j + b_j and L_j², all linear along a parameter path.
struct StewartParameters {
  std::array<Eigen::Vector3cd, 6> d;
  std::array<Eigen::Vector3cd, 6> s;
  std::array<Complex, 6> length_squared;

  static StewartParameters from_joints(const std::array<Eigen::Vector3cd, 6>& base,
                                       const std::array<Eigen::Vector3cd, 6>& platform,
                                       const std::array<Complex, 6>& length_squared);
  /// this − other: the rate of a straight parameter path from `other` to this.
  StewartParameters minus(const StewartParameters& other) const;
  /// this + t·rate: the point at t of a straight parameter path.
  StewartParameters lerp_rate(const StewartParameters& rate, double t) const;
};

/// The 8 equations at parameters `p` with chart `chart`: values, Jacobian in x, and the derivative along a
/// parameter path.
class StewartSystem {
 public:
  explicit StewartSystem(const Eigen::Vector4cd& chart) : chart_(chart) {}
  const Eigen::Vector4cd& chart() const { return chart_; }

  void evaluate(const StewartParameters& p, const StudyPoint& x, StudyPoint& f) const;
  void jacobian(const StewartParameters& p, const StudyPoint& x, StudyJacobian& jx) const;
  /// ∂f/∂t for parameters moving at rate `dp` (same layout as StewartParameters: d, s, L² rates).
  void parameter_derivative(const StewartParameters& p, const StewartParameters& dp, const StudyPoint& x,
                            StudyPoint& ft) const;

  /// All of the above in one pass (the tracker's hot path): f and ft are filled in when not null; `dp` is
  /// needed only with ft.
  void linearise(const StewartParameters& p, const StewartParameters* dp, const StudyPoint& x, StudyPoint* f,
                 StudyJacobian& jx, StudyPoint* ft) const;

  /// The Taylor coefficients of the solution path through x(0) = taylor[0] as the parameters move from `p` at
  /// rate `dp`: x(s) = Σ taylor[k]·s^k. Given taylor[0] and `lu`, a factorisation of the Jacobian at (or
  /// near) taylor[0], fills in taylor[1] … taylor[order] (order ≤ 5). Each order costs one pass over the legs
  /// and one solve: the coefficient of s^k of f(x(s), p + s·dp) is J·x_k + r_k with r_k depending on the
  /// lower orders only, so x_k = −J⁻¹ r_k (x_1 is the velocity −J⁻¹·∂f/∂t).
  void path_taylor(const StewartParameters& p, const StewartParameters& dp, const ComplexLu<8>& lu, int order,
                   StudyPoint* taylor) const;

  /// The squared lengths that make `x` a solution at the joints of `p` (its lengths are ignored): how a start
  /// instance with a known solution is made (monodromy).
  std::array<Complex, 6> lengths_through(const StewartParameters& p, const StudyPoint& x) const;

 private:
  Eigen::Vector4cd chart_;
};

/// y = M e for d, s (see the header comment).
Eigen::Vector4cd leg_quaternion(const Eigen::Vector3cd& d, const Eigen::Vector3cd& s,
                                const Eigen::Vector4cd& e);

}  // namespace pkm
