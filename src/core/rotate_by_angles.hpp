#pragma once
// A convention's rotation applied to vectors as its three elementary rotations in turn, without forming the
// matrix: for the hexapod's hot IK from the coordinates (kinematics/strut_lengths.cpp), where it takes 12
// products and 6 sums per vector against 14 + 5 for the matrix's entries and 9 + 6 for the product.
// Equal to rotation_entries' matrix times the vector to rounding (a few units in the last place; the tests
// compare them), not to its bits. Inline, so that a caller's AVX2 or AVX-512 copy compiles it along with its
// work; plain IEEE operations in a fixed order, so every copy gives the same bits, provided the caller fuses
// no multiply–add (see core/rotation_from_sines.hpp).
#include "core/rotation.hpp"

namespace pkm {

namespace elementary_detail {

// The active rotation by the angle of sine s and cosine c about axis x, y or z: the two coordinates it
// changes, (u, v) → (c·u − s·v, s·u + c·v), u and v in the axis' cyclic order (y, z), (z, x), (x, y).
template <class V, class S>
inline void turn(const S& s, const S& c, V& u, V& v) noexcept {
#if defined(__clang__)
#pragma clang fp contract(off)  // no fused multiply–add, even where the target has it: the same bits
#endif
  const V turned_u = c * u - s * v;
  v = s * u + c * v;
  u = turned_u;
}

// The same by the angle's negative (sin(−θ) = −s): (u, v) → (c·u + s·v, c·v − s·u).
template <class V, class S>
inline void turn_back(const S& s, const S& c, V& u, V& v) noexcept {
#if defined(__clang__)
#pragma clang fp contract(off)
#endif
  const V turned_u = c * u + s * v;
  v = c * v - s * u;
  u = turned_u;
}

}  // namespace elementary_detail

/// (x, y, z) ← R·(x, y, z), R `convention`'s rotation of angles with sines s1, s2, s3 and cosines c1, c2, c3
/// (as rotation_entries): the rightmost elementary rotation of its product first. V a double or a vector of
/// them (a vector per lane), S the same or a double for every lane.
template <class V, class S>
inline void rotate_by_angles(AngleConvention convention, const S& s1, const S& s2, const S& s3, const S& c1,
                             const S& c2, const S& c3, V& x, V& y, V& z) noexcept {
  using elementary_detail::turn;
  using elementary_detail::turn_back;
  switch (convention) {
    case AngleConvention::abc:  // Rz(C)Ry(B)Rx(A)
      turn(s1, c1, y, z);
      turn(s2, c2, z, x);
      turn(s3, c3, x, y);
      return;
    case AngleConvention::krylov:  // Rz(-ψ)Rx(-ϑ)Ry(-γ)
      turn_back(s3, c3, z, x);
      turn_back(s2, c2, y, z);
      turn_back(s1, c1, x, y);
      return;
    case AngleConvention::euler_zxz:  // Rz(ψ)Rx(ϑ)Rz(φ)
      turn(s3, c3, x, y);
      turn(s2, c2, y, z);
      turn(s1, c1, x, y);
      return;
  }
}

}  // namespace pkm
