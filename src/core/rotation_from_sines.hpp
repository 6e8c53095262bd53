#pragma once
// A convention's rotation matrix from its three angles' sines and cosines, for the conversions on the IK hot
// path (core/rotation.cpp): inline, so that a caller's AVX2 or AVX-512 copy
// compiles it along with its work. Every entry by plain IEEE operations in a fixed order: the same bits in
// every copy, provided the caller fuses no multiply–add (a target with FMA under GCC needs
// `#pragma GCC optimize("fp-contract=off")` around the caller, as in kinematics/strut_lengths.cpp).
#include <Eigen/Core>

#include "core/rotation.hpp"

namespace pkm {

/// The closed form of `convention`'s matrix, row by row into r[0..8], from s_k = sin(angle k) and c_k =
/// cos(angle k); T a double, or a vector of them for a kernel that wants every entry in all lanes (each entry
/// by the same operations either way). The tests check the forms against the products of elementary
/// rotations that define the conventions.
template <class T>
inline void rotation_entries(AngleConvention convention, const T& s1, const T& s2, const T& s3, const T& c1,
                             const T& c2, const T& c3, T* r) {
#if defined(__clang__)
#pragma clang fp contract(off)  // no fused multiply–add, even where the target has it: the same bits
#endif
  const T zero{}, one = zero + 1.0;
  switch (convention) {
    case AngleConvention::abc:  // Rz(C)Ry(B)Rx(A), (A, B, C) = angles; eq. 12
      r[0] = c2 * c3, r[1] = s1 * s2 * c3 - c1 * s3, r[2] = c1 * s2 * c3 + s1 * s3;
      r[3] = c2 * s3, r[4] = s1 * s2 * s3 + c1 * c3, r[5] = c1 * s2 * s3 - s1 * c3;
      r[6] = -s2, r[7] = s1 * c2, r[8] = c1 * c2;
      return;
    case AngleConvention::krylov:  // Rz(-ψ)Rx(-ϑ)Ry(-γ), (ψ, ϑ, γ) = angles; eq. 15 (rows l, m, n)
      r[0] = c1 * c3 + s2 * s1 * s3, r[1] = s1 * c2, r[2] = s1 * s2 * c3 - c1 * s3;
      r[3] = c1 * s2 * s3 - s1 * c3, r[4] = c1 * c2, r[5] = s1 * s3 + c1 * s2 * c3;
      r[6] = c2 * s3, r[7] = -s2, r[8] = c2 * c3;
      return;
    case AngleConvention::euler_zxz:  // Rz(ψ)Rx(ϑ)Rz(φ), (ψ, ϑ, φ) = angles; eq. 13
      r[0] = c1 * c3 - c2 * s1 * s3, r[1] = -c1 * s3 - c2 * s1 * c3, r[2] = s1 * s2;
      r[3] = s1 * c3 + c2 * c1 * s3, r[4] = -s1 * s3 + c2 * c1 * c3, r[5] = -c1 * s2;
      r[6] = s2 * s3, r[7] = s2 * c3, r[8] = c2;
      return;
  }
  r[0] = one, r[1] = zero, r[2] = zero, r[3] = zero, r[4] = one, r[5] = zero, r[6] = zero, r[7] = zero,
  r[8] = one;
}

/// rotation_entries as a matrix, sines[k] = sin(angles[k]), cosines[k] = cos(angles[k]).
inline Eigen::Matrix3d rotation_from_sines(AngleConvention convention, const double* sines,
                                           const double* cosines) {
  double r[9];
  rotation_entries(convention, sines[0], sines[1], sines[2], cosines[0], cosines[1], cosines[2], r);
  return Eigen::Matrix<double, 3, 3, Eigen::RowMajor>(r);
}

}  // namespace pkm
