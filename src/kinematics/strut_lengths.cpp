#include "kinematics/strut_lengths.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/rotate_by_angles.hpp"
#include "core/rotation_kernels.hpp"
#include "core/sincos3.hpp"
#include "core/wide_kernels.hpp"
#if defined(__SSE2__)
#include <immintrin.h>
#endif

// No fused multiply–add anywhere in this file: GCC 12 fuses them in C++ mode where the target has them (the
// AVX-512 copy below), which would give other bits than the baseline copy. Popped at the end (unity builds).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif

namespace pkm {
namespace {

// Struts in the lanes of a vector: two per SSE2 pair (three pairs); in the AVX2 copy four per quad (struts
// 0–3 and 4–7, 6 and 7 the layout's zero padding); in the AVX-512 copy all eight lanes in one vector (the
// padding's lanes computed and dropped: a masked store).
using StrutPair = double __attribute__((vector_size(16)));
#if PKM_HAS_WIDE_KERNELS
using StrutQuad = double __attribute__((vector_size(32)));
using StrutOct = double __attribute__((vector_size(64)));
#endif

// One strut per lane: the platform joints b and base joints a by coordinate.
template <class V>
struct StrutLanes {
  V bx, by, bz, ax, ay, az;
};

// `squared`: the squared lengths |d|² of the lanes' struts at the pose of rotation r (r(i, j)) and position p
// (p[k]): d = (R·b)_xyz + (p − a), the rotation's first two products summed apart from the third and the
// offset (a short dependency chain), |d|² = (dx² + dy²) + dz². Each operation is one IEEE operation per lane
// (the entries scalars, or vectors holding an entry in every lane): a strut's value does not depend on the
// vector's width.
template <class V, class Rotation, class Position>
inline void squared_lengths(const StrutLanes<V>& s, const Rotation& r, const Position& p,
                            V& squared) noexcept {
#if defined(__clang__)
#pragma clang fp contract(off)  // no fused multiply–add, even where the target has it: the same bits
#endif
  const V dx = (r(0, 0) * s.bx + r(0, 1) * s.by) + (r(0, 2) * s.bz + (p[0] - s.ax));
  const V dy = (r(1, 0) * s.bx + r(1, 1) * s.by) + (r(1, 2) * s.bz + (p[1] - s.ay));
  const V dz = (r(2, 0) * s.bx + r(2, 1) * s.by) + (r(2, 2) * s.bz + (p[2] - s.az));
  squared = (dx * dx + dy * dy) + dz * dz;
}

template <class V>
inline void squared_lengths(const StrutLanes<V>& s, const Pose& pose, V& squared) noexcept {
  squared_lengths(s, pose.rotation, pose.position_mm, squared);
}

// `squared` from the coordinates: the platform joints turned by the convention's elementary rotations
// (sines s[k], cosines c[k], k = 0, 1, 2; S a double or a vector holding the value in every lane), then
// d = Rb + (p − a) and |d|² as above. Fewer operations than the matrix and its product.
template <class V, class S, class Position>
inline void squared_lengths_at(AngleConvention convention, const S* s, const S* c,
                               const StrutLanes<V>& struts, const Position& p, V& squared) noexcept {
#if defined(__clang__)
#pragma clang fp contract(off)
#endif
  V x = struts.bx, y = struts.by, z = struts.bz;
  rotate_by_angles(convention, s[0], s[1], s[2], c[0], c[1], c[2], x, y, z);
  const V dx = x + (p[0] - struts.ax);
  const V dy = y + (p[1] - struts.ay);
  const V dz = z + (p[2] - struts.az);
  squared = (dx * dx + dy * dy) + dz * dz;
}

// Struts first … first + lanes − 1 of `layout`, loaded whole (the lanes lie within the padded rows).
template <class V>
inline void load_struts(const SixStrutLayout& layout, int first, StrutLanes<V>& s) noexcept {
  constexpr int kRow = SixStrutLayout::Rows::ColsAtCompileTime;
  const double* b = layout.platform_mm.data() + first;
  const double* a = layout.base_mm.data() + first;
  std::memcpy(&s.bx, b, sizeof(V));
  std::memcpy(&s.by, b + kRow, sizeof(V));
  std::memcpy(&s.bz, b + 2 * kRow, sizeof(V));
  std::memcpy(&s.ax, a, sizeof(V));
  std::memcpy(&s.ay, a + kRow, sizeof(V));
  std::memcpy(&s.az, a + 2 * kRow, sizeof(V));
}

// Whether both lanes are > 0 (false for a zero or NaN length).
bool positive(const StrutPair& v) noexcept {
#if defined(__SSE2__)
  return _mm_movemask_pd(_mm_cmpgt_pd(v, _mm_setzero_pd())) == 3;
#else
  return v[0] > 0.0 && v[1] > 0.0;
#endif
}

inline StrutPair root(const StrutPair& squared) noexcept {
#if defined(__SSE2__)
  return _mm_sqrt_pd(squared);  // correctly rounded, as std::sqrt
#else
  return StrutPair{std::sqrt(squared[0]), std::sqrt(squared[1])};
#endif
}

// The three pairs' lengths from `squared_of(struts, squared)`. All lanes are computed before any is stored:
// the lengths' storage might alias the pose, which would make the compiler read the pose again after each
// store.
template <class SquaredOf>
inline bool pairs_lengths(const SixStrutLayout& layout, const SquaredOf& squared_of,
                          double* lengths_mm) noexcept {
  StrutPair lengths[3];
  for (int pair = 0; pair < 3; ++pair) {
    StrutLanes<StrutPair> struts;
    load_struts(layout, 2 * pair, struts);
    StrutPair squared;
    squared_of(struts, squared);
    lengths[pair] = root(squared);
  }
  std::memcpy(lengths_mm, lengths, sizeof lengths);
  return positive(lengths[0]) && positive(lengths[1]) && positive(lengths[2]);
}

bool six_strut_lengths_pairs(const SixStrutLayout& layout, const Pose& pose, double* lengths_mm) noexcept {
  return pairs_lengths(
      layout,
      [&](const StrutLanes<StrutPair>& struts, StrutPair& squared) {
        squared_lengths(struts, pose, squared);
      },
      lengths_mm);
}

// From the coordinates: the baseline sines and cosines (the C library's where an angle needs them) and the
// baseline lanes. Out of line: the vector copies that fall back to it stay leaf functions.
[[gnu::noinline]] bool lengths_at_baseline(const SixStrutLayout& layout, AngleConvention convention,
                                           const PoseVector& coordinates, double* lengths_mm) noexcept {
  double sines[3], cosines[3];
  sincos3_baseline(coordinates.data() + 3, sines, cosines);
  const double* position = coordinates.data();
  return pairs_lengths(
      layout,
      [&](const StrutLanes<StrutPair>& struts, StrutPair& squared) {
        squared_lengths_at(convention, sines, cosines, struts, position, squared);
      },
      lengths_mm);
}

#if PKM_HAS_WIDE_KERNELS
// The AVX2 copy, without fused multiply–adds: the same operations per strut, so the same bits. The lengths
// of the squares of struts 0–3 and 4–7 (6 and 7: the padding's, dropped).
[[gnu::target("avx2")]] inline bool quad_roots(const StrutQuad& squared0123, const StrutQuad& squared4567,
                                               double* lengths_mm) noexcept {
  const __m256d l0123 = _mm256_sqrt_pd(squared0123), l4567 = _mm256_sqrt_pd(squared4567);
  _mm256_storeu_pd(lengths_mm, l0123);
  _mm_storeu_pd(lengths_mm + 4, _mm256_castpd256_pd128(l4567));
  const __m256d zero = _mm256_setzero_pd();
  return (_mm256_movemask_pd(_mm256_cmp_pd(l0123, zero, _CMP_GT_OQ)) |
          (_mm256_movemask_pd(_mm256_cmp_pd(l4567, zero, _CMP_GT_OQ)) & 3) << 4) == 63;
}

[[gnu::target("avx2")]] inline bool quad_lengths(const SixStrutLayout& layout, const Pose& pose,
                                                 double* lengths_mm) noexcept {
  StrutLanes<StrutQuad> first, last;
  load_struts(layout, 0, first);
  load_struts(layout, 4, last);
  StrutQuad squared0123, squared4567;
  squared_lengths(first, pose, squared0123);
  squared_lengths(last, pose, squared4567);
  return quad_roots(squared0123, squared4567, lengths_mm);
}

// The AVX-512 copy: the six struts and the padding in one vector (plain loads: a masked load costs one more
// operation on the vector ports), the same operations per strut. Fewer instructions than the AVX2 copy.
[[gnu::target("avx512f")]] inline bool oct_roots(const StrutOct& squared, double* lengths_mm) noexcept {
  constexpr __mmask8 kSix = 0x3f;
  const __m512d lengths = _mm512_maskz_sqrt_pd(0xff, squared);  // zero-masking: see spread_lane
  _mm512_mask_storeu_pd(lengths_mm, kSix, lengths);
  return _mm512_mask_cmp_pd_mask(kSix, lengths, _mm512_setzero_pd(), _CMP_GT_OQ) == kSix;
}

[[gnu::target("avx2"), gnu::flatten]] bool six_strut_lengths_quads(const SixStrutLayout& layout,
                                                                   const Pose& pose,
                                                                   double* lengths_mm) noexcept {
  return quad_lengths(layout, pose, lengths_mm);
}

[[gnu::target("avx512f"), gnu::flatten]] bool six_strut_lengths_octs(const SixStrutLayout& layout,
                                                                     const Pose& pose,
                                                                     double* lengths_mm) noexcept {
  StrutLanes<StrutOct> struts;
  load_struts(layout, 0, struts);
  StrutOct squared;
  squared_lengths(struts, pose, squared);
  return oct_roots(squared, lengths_mm);
}

// The fused copies: the angles' sines and cosines, the joints turned by the elementary rotations and the six
// lengths in one function, no matrix and no Pose. The same operations per value as lengths_at_baseline, so
// the same bits.
[[gnu::target("avx2"), gnu::flatten]] bool lengths_at_quads(const SixStrutLayout& layout,
                                                            AngleConvention convention,
                                                            const PoseVector& coordinates,
                                                            double* lengths_mm) noexcept {
  sincos3_detail::Quad s, c;
  if (!sincos3_avx2_lanes(coordinates.data() + 3, s, c))
    return lengths_at_baseline(layout, convention, coordinates, lengths_mm);
  const double sines[3] = {s[0], s[1], s[2]}, cosines[3] = {c[0], c[1], c[2]};
  const double* position = coordinates.data();
  StrutLanes<StrutQuad> first, last;
  load_struts(layout, 0, first);
  load_struts(layout, 4, last);
  StrutQuad squared0123, squared4567;
  squared_lengths_at(convention, sines, cosines, first, position, squared0123);
  squared_lengths_at(convention, sines, cosines, last, position, squared4567);
  return quad_roots(squared0123, squared4567, lengths_mm);
}

// Lane `lane` of `sc` in every lane (the permutation's indices from row `lane` of `table`). A function of
// its own, not a lambda: clang does not give a lambda its enclosing function's target.
[[gnu::target("avx512f")]] inline StrutOct spread_lane(const sincos3_detail::Oct& sc,
                                                       const std::int64_t* table, int lane) noexcept {
  return _mm512_maskz_permutexvar_pd(0xff, _mm512_load_si512(table + 8 * lane), sc);
}

[[gnu::target("avx512f"), gnu::flatten]] bool lengths_at_octs(const SixStrutLayout& layout,
                                                              AngleConvention convention,
                                                              const PoseVector& coordinates,
                                                              double* lengths_mm) noexcept {
  sincos3_detail::Oct sc;
  if (!sincos3_avx512_lanes(coordinates.data() + 3, sc))
    return lengths_at_baseline(layout, convention, coordinates, lengths_mm);
  // The sines and cosines spread over the lanes (each in all of them) and the position loaded into them, so
  // that every strut's operations are lane operations. The permutations' indices are loaded from a table
  // (hidden from the compiler by the empty asm): built from immediates, as the compiler would, each would
  // cost one more instruction on the two ports that run AVX-512. (A store and six broadcast loads instead of
  // the permutations: 4 % slower, Xeon of 2023, the loads waiting for the store.) The zero-masking
  // permutation for GCC 12 (see core/sincos3.hpp).
  alignas(64) static constexpr std::int64_t kLane[7][8] = {
      {0, 0, 0, 0, 0, 0, 0, 0}, {1, 1, 1, 1, 1, 1, 1, 1}, {2, 2, 2, 2, 2, 2, 2, 2}, {3, 3, 3, 3, 3, 3, 3, 3},
      {4, 4, 4, 4, 4, 4, 4, 4}, {5, 5, 5, 5, 5, 5, 5, 5}, {6, 6, 6, 6, 6, 6, 6, 6}};
  const std::int64_t* table = &kLane[0][0];
  asm("" : "+r"(table));
  const StrutOct sines[3] = {spread_lane(sc, table, 0), spread_lane(sc, table, 1), spread_lane(sc, table, 2)};
  const StrutOct cosines[3] = {spread_lane(sc, table, 4), spread_lane(sc, table, 5),
                               spread_lane(sc, table, 6)};
  const StrutOct position[3] = {_mm512_set1_pd(coordinates[0]), _mm512_set1_pd(coordinates[1]),
                                _mm512_set1_pd(coordinates[2])};
  StrutLanes<StrutOct> struts;
  load_struts(layout, 0, struts);
  StrutOct squared;
  squared_lengths_at(convention, sines, cosines, struts, position, squared);
  return oct_roots(squared, lengths_mm);
}

enum class StrutKernel { pairs, quads, octs };

StrutKernel strut_kernel_of_this_processor() {
  if (!wide_kernels_available()) return StrutKernel::pairs;
  return avx512_kernels_available() ? StrutKernel::octs : StrutKernel::quads;
}

// Decided once, when the library is loaded.
const StrutKernel strut_kernel = strut_kernel_of_this_processor();
#endif

}  // namespace

bool six_strut_lengths(const SixStrutLayout& layout, const Pose& pose, double* lengths_mm) noexcept {
#if PKM_HAS_WIDE_KERNELS
  if (strut_kernel == StrutKernel::octs) return six_strut_lengths_octs(layout, pose, lengths_mm);
  if (strut_kernel == StrutKernel::quads) return six_strut_lengths_quads(layout, pose, lengths_mm);
#endif
  return six_strut_lengths_pairs(layout, pose, lengths_mm);
}

bool six_strut_lengths_baseline(const SixStrutLayout& layout, const Pose& pose, double* lengths_mm) noexcept {
  return six_strut_lengths_pairs(layout, pose, lengths_mm);
}

bool six_strut_lengths_at(const SixStrutLayout& layout, AngleConvention convention,
                          const PoseVector& coordinates, double* lengths_mm) noexcept {
#if PKM_HAS_WIDE_KERNELS
  if (strut_kernel == StrutKernel::octs) return lengths_at_octs(layout, convention, coordinates, lengths_mm);
  if (strut_kernel == StrutKernel::quads)
    return lengths_at_quads(layout, convention, coordinates, lengths_mm);
#endif
  return lengths_at_baseline(layout, convention, coordinates, lengths_mm);
}

int strut_kernel_count() noexcept {
#if PKM_HAS_WIDE_KERNELS
  return static_cast<int>(strut_kernel) + 1;
#else
  return 1;
#endif
}

bool six_strut_lengths_at_kernel(int kernel, const SixStrutLayout& layout, AngleConvention convention,
                                 const PoseVector& coordinates, double* lengths_mm) noexcept {
#if PKM_HAS_WIDE_KERNELS
  if (kernel == 2) return lengths_at_octs(layout, convention, coordinates, lengths_mm);
  if (kernel == 1) return lengths_at_quads(layout, convention, coordinates, lengths_mm);
#endif
  return lengths_at_baseline(layout, convention, coordinates, lengths_mm);
}

}  // namespace pkm

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif
