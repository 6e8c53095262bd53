#include "kinematics/strut_lengths.hpp"

#include <cmath>
#include <cstring>

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
// 0–3 and 2–5: struts 2 and 3 twice, by the same operations); in the AVX-512 copy all six in one vector of
// eight (masked loads and store).
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

// `squared`: the squared lengths |d|² of the lanes' struts at `pose`: d = (R·b)_xyz + (p − a), the rotation's
// first two products summed apart from the third and the offset (a short dependency chain), |d|² = (dx² +
// dy²) + dz². Each operation is one IEEE operation per lane: a strut's value does not depend on the vector's
// width.
template <class V>
inline void squared_lengths(const StrutLanes<V>& s, const Pose& pose, V& squared) noexcept {
#if defined(__clang__)
#pragma clang fp contract(off)  // no fused multiply–add, even where the target has it: the same bits
#endif
  const Eigen::Matrix3d& r = pose.rotation;
  const V dx = (r(0, 0) * s.bx + r(0, 1) * s.by) + (r(0, 2) * s.bz + (pose.position_mm.x() - s.ax));
  const V dy = (r(1, 0) * s.bx + r(1, 1) * s.by) + (r(1, 2) * s.bz + (pose.position_mm.y() - s.ay));
  const V dz = (r(2, 0) * s.bx + r(2, 1) * s.by) + (r(2, 2) * s.bz + (pose.position_mm.z() - s.az));
  squared = (dx * dx + dy * dy) + dz * dz;
}

// Struts first … first + lanes − 1 of `layout`, loaded whole (the lanes lie within the rows).
template <class V>
inline void load_struts(const SixStrutLayout& layout, int first, StrutLanes<V>& s) noexcept {
  const double* b = layout.platform_mm.data() + first;
  const double* a = layout.base_mm.data() + first;
  std::memcpy(&s.bx, b, sizeof(V));
  std::memcpy(&s.by, b + 6, sizeof(V));
  std::memcpy(&s.bz, b + 12, sizeof(V));
  std::memcpy(&s.ax, a, sizeof(V));
  std::memcpy(&s.ay, a + 6, sizeof(V));
  std::memcpy(&s.az, a + 12, sizeof(V));
}

// Whether both lanes are > 0 (false for a zero or NaN length).
bool positive(const StrutPair& v) noexcept {
#if defined(__SSE2__)
  return _mm_movemask_pd(_mm_cmpgt_pd(v, _mm_setzero_pd())) == 3;
#else
  return v[0] > 0.0 && v[1] > 0.0;
#endif
}

inline StrutPair pair_lengths(const SixStrutLayout& layout, const Pose& pose, int first) noexcept {
  StrutLanes<StrutPair> s;
  load_struts(layout, first, s);
  StrutPair squared;
  squared_lengths(s, pose, squared);
#if defined(__SSE2__)
  return _mm_sqrt_pd(squared);  // correctly rounded, as std::sqrt
#else
  return StrutPair{std::sqrt(squared[0]), std::sqrt(squared[1])};
#endif
}

// All lanes are computed before any is stored: the lengths' storage might alias the pose, which would make
// the compiler read the pose again after each store.
bool six_strut_lengths_pairs(const SixStrutLayout& layout, const Pose& pose, double* lengths_mm) noexcept {
  const StrutPair l01 = pair_lengths(layout, pose, 0);
  const StrutPair l23 = pair_lengths(layout, pose, 2);
  const StrutPair l45 = pair_lengths(layout, pose, 4);
  std::memcpy(lengths_mm, &l01, sizeof l01);
  std::memcpy(lengths_mm + 2, &l23, sizeof l23);
  std::memcpy(lengths_mm + 4, &l45, sizeof l45);
  return positive(l01) && positive(l23) && positive(l45);
}

#if PKM_HAS_WIDE_KERNELS
// The AVX2 copy, without fused multiply–adds: the same operations per strut, so the same bits.
[[gnu::target("avx2"), gnu::flatten]] bool six_strut_lengths_quads(const SixStrutLayout& layout,
                                                                   const Pose& pose,
                                                                   double* lengths_mm) noexcept {
  StrutLanes<StrutQuad> first, last;
  load_struts(layout, 0, first);
  load_struts(layout, 2, last);
  StrutQuad squared0123, squared2345;
  squared_lengths(first, pose, squared0123);
  squared_lengths(last, pose, squared2345);
  const __m256d l0123 = _mm256_sqrt_pd(squared0123), l2345 = _mm256_sqrt_pd(squared2345);
  _mm256_storeu_pd(lengths_mm, l0123);
  _mm_storeu_pd(lengths_mm + 4, _mm256_extractf128_pd(l2345, 1));
  const __m256d zero = _mm256_setzero_pd();
  return (_mm256_movemask_pd(_mm256_cmp_pd(l0123, zero, _CMP_GT_OQ)) &
          _mm256_movemask_pd(_mm256_cmp_pd(l2345, zero, _CMP_GT_OQ))) == 15;
}

// The AVX-512 copy: the six struts in one vector (lanes 6 and 7 masked off), the same operations per strut.
// Fewer instructions than the AVX2 copy: 8 % less time for the whole hot IK, conversion included (Xeon of
// 2023).
[[gnu::target("avx512f"), gnu::flatten]] bool six_strut_lengths_octs(const SixStrutLayout& layout,
                                                                     const Pose& pose,
                                                                     double* lengths_mm) noexcept {
  constexpr __mmask8 kSix = 0x3f;
  const double* b = layout.platform_mm.data();
  const double* a = layout.base_mm.data();
  StrutLanes<StrutOct> s;
  s.bx = _mm512_maskz_loadu_pd(kSix, b);
  s.by = _mm512_maskz_loadu_pd(kSix, b + 6);
  s.bz = _mm512_maskz_loadu_pd(kSix, b + 12);
  s.ax = _mm512_maskz_loadu_pd(kSix, a);
  s.ay = _mm512_maskz_loadu_pd(kSix, a + 6);
  s.az = _mm512_maskz_loadu_pd(kSix, a + 12);
  StrutOct squared;
  squared_lengths(s, pose, squared);
  const __m512d lengths = _mm512_maskz_sqrt_pd(kSix, squared);
  _mm512_mask_storeu_pd(lengths_mm, kSix, lengths);
  return _mm512_mask_cmp_pd_mask(kSix, lengths, _mm512_setzero_pd(), _CMP_GT_OQ) == kSix;
}

enum class StrutKernel { pairs, quads, octs };

StrutKernel strut_kernel_of_this_processor() {
  if (!wide_kernels_available()) return StrutKernel::pairs;
  return __builtin_cpu_supports("avx512f") ? StrutKernel::octs : StrutKernel::quads;
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

}  // namespace pkm

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif
