#pragma once
// sin and cos of three angles at once, for the angles → matrix conversion on the IK hot path
// (rotation_from_angles): a range reduction and two short polynomials on the angles in the lanes of a vector
// (one AVX2 vector where the processor has it, two SSE2 pairs otherwise; sines and cosines in one AVX-512
// vector for the hexapod's fused kernel, kinematics/strut_lengths.cpp), instead of six calls into the C
// library. Accurate to about one unit in the last place (within 1.2e-16 of std::sin and std::cos;
// tests/core/sincos3_test.cpp), and the same bits on every processor and in every build: plain IEEE
// operations in a fixed order, no fused multiply–add.
//
// Method (Cody & Waite; Sun's fdlibm kernels): n = nearest integer to x·2/π, y = x − n·π/2 with π/2 in three
// parts (the first two of 33 bits, so that n·part is exact for |n| < 2^20), then the degree-13 odd and
// degree-14 even minimax polynomials of sin and cos on |y| ≤ π/4 and the quadrant n mod 4. When every angle
// is within ±π/4 (a platform's usual tilts) the reduction is skipped (n = 0: the same bits). Angles beyond
// ±2^19·π/2 (or not finite) go to std::sin and std::cos.
//
// Inline, so that a caller's own AVX2 copy (core/wide_kernels.hpp) compiles it for AVX2 along with its work.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/wide_kernels.hpp"
#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace pkm {
namespace sincos3_detail {

using Pair = double __attribute__((vector_size(16)));
using IntPair = std::uint64_t __attribute__((vector_size(16)));
#if PKM_HAS_WIDE_KERNELS
using Quad = double __attribute__((vector_size(32)));
using IntQuad = std::uint64_t __attribute__((vector_size(32)));
using Oct = double __attribute__((vector_size(64)));
using IntOct = std::uint64_t __attribute__((vector_size(64)));
#endif

constexpr double kLimit = 823549.6654215439;       // 2^19·π/2
constexpr double kQuarterPi = 0.7853981633974483;  // below π/4 (rounded down): no reduction needed

inline bool all_within(const double* angles, double limit) {
  return std::abs(angles[0]) <= limit && std::abs(angles[1]) <= limit && std::abs(angles[2]) <= limit;
}

// Out of line: the vector paths stay leaf functions, without the registers a library call needs saved.
[[gnu::noinline]] inline void library_sincos3(const double* angles, double* sin_out, double* cos_out) {
  for (int k = 0; k < 3; ++k) {
    sin_out[k] = std::sin(angles[k]);
    cos_out[k] = std::cos(angles[k]);
  }
}

// sin and cos of every lane of x (|x| ≤ kLimit; |x| ≤ π/4 without `reduce`), V a vector of doubles and I the
// same of 64-bit integers. A vector and a scalar combine lane by lane; every operation is one IEEE operation
// per lane, so a lane's results do not depend on the vector's width.
template <class V, class I, bool reduce>
inline void sincos_lanes(const V& x, V& sin_out, V& cos_out) noexcept {
#if defined(__clang__)
#pragma clang fp contract(off)  // no fused multiply–add, even where the target has it: the same bits
#endif
  V y = x;
  I quadrant = {};
  if constexpr (reduce) {
    // n = x·2/π rounded to the nearest integer: adding 1.5·2^52 rounds, and the sum's low mantissa bits are n
    // (two's complement).
    constexpr double kShift = 0x1.8p52;
    const V shifted = x * 0x1.45f306dc9c883p-1 + kShift;
    const V n = shifted - kShift;
    std::memcpy(&quadrant, &shifted, sizeof quadrant);
    y = ((x - n * 0x1.921fb544p+0) - n * 0x1.0b4611a6p-34) - n * 0x1.3198a2e037073p-69;
  }
  // fdlibm's __kernel_sin and __kernel_cos polynomials (without the tail of the reduced argument), summed by
  // Estrin's scheme (pairs of terms, then the powers z², z⁴) for a short dependency chain.
  const V z = y * y;
  const V z2 = z * z;
  const V z4 = z2 * z2;
  const V sin_poly = (-1.66666666666666324348e-01 + z * 8.33333333332248946124e-03) +
                     z2 * (-1.98412698298579493134e-04 + z * 2.75573137070700676789e-06) +
                     z4 * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10);
  const V s = y + (z * y) * sin_poly;
  const V cos_poly = (4.16666666666666019037e-02 + z * -1.38888888888741095749e-03) +
                     z2 * (2.48015872894767294178e-05 + z * -2.75573143513906633035e-07) +
                     z4 * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11);
  const V half_z = 0.5 * z;
  const V w = 1.0 - half_z;
  const V c = w + (((1.0 - w) - half_z) + z2 * cos_poly);
  // sin(y) has the sign of y for |y| ≤ π/4, including sin(−0) = −0, which the sum above loses.
  constexpr std::uint64_t kSignBit = std::uint64_t{1} << 63;
  I s_bits, c_bits, y_bits;
  std::memcpy(&s_bits, &s, sizeof s_bits);
  std::memcpy(&c_bits, &c, sizeof c_bits);
  std::memcpy(&y_bits, &y, sizeof y_bits);
  s_bits = (s_bits & ~kSignBit) | (y_bits & kSignBit);
  if constexpr (reduce) {
    // The quadrant: odd n swaps sin and cos; sin changes sign in quadrants 2 and 3, cos in 1 and 2.
    const I swap = -(quadrant & 1);
    const I sin_bits = ((s_bits & ~swap) | (c_bits & swap)) ^ ((quadrant & 2) << 62);
    const I cos_bits = ((c_bits & ~swap) | (s_bits & swap)) ^ (((quadrant + 1) & 2) << 62);
    s_bits = sin_bits;
    c_bits = cos_bits;
  }
  std::memcpy(&sin_out, &s_bits, sizeof sin_out);
  std::memcpy(&cos_out, &c_bits, sizeof cos_out);
}

template <bool reduce>
inline void pairs_sincos3(const double* angles, double* sin_out, double* cos_out) noexcept {
  Pair x01 = {angles[0], angles[1]}, x2 = {angles[2], angles[2]};
#if defined(__GNUC__) && defined(__SSE2__)
  // The second pair stays a vector operation: with two equal lanes the compiler would compute it in scalars
  // and rebuild every constant of the first pair from a scalar, which costs more than the lane it saves.
  asm("" : "+x"(x2));
#endif
  Pair s01, c01, s2, c2;
  sincos_lanes<Pair, IntPair, reduce>(x01, s01, c01);
  sincos_lanes<Pair, IntPair, reduce>(x2, s2, c2);
  sin_out[0] = s01[0];
  sin_out[1] = s01[1];
  sin_out[2] = s2[0];
  cos_out[0] = c01[0];
  cos_out[1] = c01[1];
  cos_out[2] = c2[0];
}

#if PKM_HAS_WIDE_KERNELS
// *p, loaded by itself: the empty asm keeps the compiler from merging it with a neighbour's load.
inline double loaded_alone(const double* p) noexcept {
  double v = *p;
  asm("" : "+x"(v));
  return v;
}

// fdlibm's sin coefficients (lanes 0–3) beside its cos coefficients (lanes 4–7), those of sincos_lanes.
constexpr Oct kPoly0 = {-1.66666666666666324348e-01, -1.66666666666666324348e-01, -1.66666666666666324348e-01,
                        -1.66666666666666324348e-01, 4.16666666666666019037e-02,  4.16666666666666019037e-02,
                        4.16666666666666019037e-02,  4.16666666666666019037e-02};
constexpr Oct kPoly1 = {8.33333333332248946124e-03,  8.33333333332248946124e-03,  8.33333333332248946124e-03,
                        8.33333333332248946124e-03,  -1.38888888888741095749e-03, -1.38888888888741095749e-03,
                        -1.38888888888741095749e-03, -1.38888888888741095749e-03};
constexpr Oct kPoly2 = {-1.98412698298579493134e-04, -1.98412698298579493134e-04, -1.98412698298579493134e-04,
                        -1.98412698298579493134e-04, 2.48015872894767294178e-05,  2.48015872894767294178e-05,
                        2.48015872894767294178e-05,  2.48015872894767294178e-05};
constexpr Oct kPoly3 = {2.75573137070700676789e-06,  2.75573137070700676789e-06,  2.75573137070700676789e-06,
                        2.75573137070700676789e-06,  -2.75573143513906633035e-07, -2.75573143513906633035e-07,
                        -2.75573143513906633035e-07, -2.75573143513906633035e-07};
constexpr Oct kPoly4 = {-2.50507602534068634195e-08, -2.50507602534068634195e-08, -2.50507602534068634195e-08,
                        -2.50507602534068634195e-08, 2.08757232129817482790e-09,  2.08757232129817482790e-09,
                        2.08757232129817482790e-09,  2.08757232129817482790e-09};
constexpr Oct kPoly5 = {1.58969099521155010221e-10,  1.58969099521155010221e-10,  1.58969099521155010221e-10,
                        1.58969099521155010221e-10,  -1.13596475577881948265e-11, -1.13596475577881948265e-11,
                        -1.13596475577881948265e-11, -1.13596475577881948265e-11};
constexpr __mmask8 kSineLanes = 0x0f;

// sincos_lanes in one AVX-512 vector whose lanes 0–3 and 4–7 hold the same angles: the sines in the first
// half, the cosines in the second, both polynomials in one chain (each lane takes its own coefficients). Per
// lane the same IEEE operations as sincos_lanes (a sine lane's y + (−0 + zy·p) is y + zy·p exactly), so the
// same bits. The caller must fuse no multiply–add (AVX-512 has FMA; see core/rotation_from_sines.hpp).
template <bool reduce>
[[gnu::target("avx512f")]] inline Oct sincos_oct(const Oct& x) noexcept {
#if defined(__clang__)
#pragma clang fp contract(off)
#endif
  Oct y = x;
  IntOct quadrant = {};
  if constexpr (reduce) {
    constexpr double kShift = 0x1.8p52;
    const Oct shifted = x * 0x1.45f306dc9c883p-1 + kShift;
    const Oct n = shifted - kShift;
    std::memcpy(&quadrant, &shifted, sizeof quadrant);
    y = ((x - n * 0x1.921fb544p+0) - n * 0x1.0b4611a6p-34) - n * 0x1.3198a2e037073p-69;
  }
  const Oct z = y * y;
  const Oct z2 = z * z;
  const Oct z4 = z2 * z2;
  const Oct poly = (kPoly0 + z * kPoly1) + z2 * (kPoly2 + z * kPoly3) + z4 * (kPoly4 + z * kPoly5);
  // sin: y + (z·y)·poly; cos: w + (((1 − w) − z/2) + z²·poly), w = 1 − z/2: both as a + (b + m·poly).
  const Oct half_z = 0.5 * z;
  const Oct w = 1.0 - half_z;
  const Oct a = _mm512_mask_blend_pd(kSineLanes, w, y);
  const Oct b = _mm512_mask_blend_pd(kSineLanes, (1.0 - w) - half_z, _mm512_set1_pd(-0.0));
  const Oct m = _mm512_mask_blend_pd(kSineLanes, z2, z * y);
  const Oct r = a + (b + m * poly);
  // The sines take the sign of y (sin(−0) = −0), the cosines keep theirs.
  constexpr std::uint64_t kSignBit = std::uint64_t{1} << 63;
  constexpr IntOct kSineSign = {kSignBit, kSignBit, kSignBit, kSignBit, 0, 0, 0, 0};
  IntOct r_bits, y_bits;
  std::memcpy(&r_bits, &r, sizeof r_bits);
  std::memcpy(&y_bits, &y, sizeof y_bits);
  // One bitwise select (0xca: the first operand's bits choose the second's over the third's), not three.
  r_bits = (IntOct)_mm512_ternarylogic_epi64((__m512i)kSineSign, (__m512i)y_bits, (__m512i)r_bits, 0xca);
  if constexpr (reduce) {
    // Odd n swaps a sine lane with its cosine lane (the halves swapped); the signs as in sincos_lanes: the
    // cosine lanes' quadrant counts one more.
    // The zero-masking forms: GCC 12 warns of the plain forms' undefined source as uninitialised.
    const __m512i swapped = _mm512_maskz_shuffle_i64x2(0xff, (__m512i)r_bits, (__m512i)r_bits, 0x4e);
    const IntOct swap = -(quadrant & 1);
    constexpr IntOct kCosineQuadrant = {0, 0, 0, 0, 1, 1, 1, 1};
    r_bits = ((r_bits & ~swap) | ((IntOct)swapped & swap)) ^ (((quadrant + kCosineQuadrant) & 2) << 62);
  }
  Oct out;
  std::memcpy(&out, &r_bits, sizeof out);
  return out;
}
#endif

}  // namespace sincos3_detail

/// sin_out[k] = sin(angles[k]), cos_out[k] = cos(angles[k]), k = 0, 1, 2, with SSE2 pairs. Never allocates.
inline void sincos3_baseline(const double* angles, double* sin_out, double* cos_out) noexcept {
  namespace d = sincos3_detail;  // qualified: a unity build may hold other names Quad
  if (d::all_within(angles, d::kQuarterPi)) return d::pairs_sincos3<false>(angles, sin_out, cos_out);
  if (d::all_within(angles, d::kLimit)) return d::pairs_sincos3<true>(angles, sin_out, cos_out);
  d::library_sincos3(angles, sin_out, cos_out);
}

#if PKM_HAS_WIDE_KERNELS
/// The same in one AVX2 vector, lanes (sin or cos of angle 0, 1, 2, and of 0), for callers that go on in
/// vector registers: false, lanes unset, where an angle needs the C library. Only where
/// wide_kernels_available().
[[gnu::target("avx2")]] inline bool sincos3_avx2_lanes(const double* angles, sincos3_detail::Quad& sin_out,
                                                       sincos3_detail::Quad& cos_out) noexcept {
  namespace d = sincos3_detail;  // qualified: a unity build may hold other names Quad
  const d::Quad x = {angles[0], angles[1], angles[2], 0.0};
  if (d::all_within(angles, d::kQuarterPi)) {
    d::sincos_lanes<d::Quad, d::IntQuad, false>(x, sin_out, cos_out);
    return true;
  }
  if (!d::all_within(angles, d::kLimit)) return false;
  d::sincos_lanes<d::Quad, d::IntQuad, true>(x, sin_out, cos_out);
  return true;
}

/// sincos3_baseline with one AVX2 vector (the same bits). Only where wide_kernels_available().
[[gnu::target("avx2")]] inline void sincos3_avx2(const double* angles, double* sin_out,
                                                 double* cos_out) noexcept {
  sincos3_detail::Quad s, c;
  if (!sincos3_avx2_lanes(angles, s, c)) return sincos3_detail::library_sincos3(angles, sin_out, cos_out);
  for (int k = 0; k < 3; ++k) {
    sin_out[k] = s[k];
    cos_out[k] = c[k];
  }
}

/// The three angles' sines in lanes 0–2 and cosines in lanes 4–6 of one AVX-512 vector (lanes 3 and 7: those
/// of 0), the same bits as sincos3_baseline; false, lanes unset, where an angle needs the C library. Inline
/// for a caller's AVX-512 copy, which must fuse no multiply–add (see core/rotation_from_sines.hpp). Only
/// where avx512_kernels_available().
[[gnu::target("avx512f")]] inline bool sincos3_avx512_lanes(const double* angles,
                                                            sincos3_detail::Oct& sincos) noexcept {
  namespace d = sincos3_detail;  // qualified: a unity build may hold other names Quad
  // Loaded one by one: the caller has usually just stored them so, and a wider load (which the compiler would
  // make of two) would wait for those stores to reach the cache: no store forwarding, about 25 ns a call.
  const __m128d angles01 = _mm_unpacklo_pd(_mm_set_sd(angles[0]), _mm_set_sd(d::loaded_alone(angles + 1)));
  const __m256d angles4 = _mm256_insertf128_pd(_mm256_castpd128_pd256(angles01), _mm_set_sd(angles[2]), 1);
  // The three angles (and 0) in both halves; the zero-masking form for GCC 12 (see sincos_oct).
  const d::Oct x = _mm512_maskz_broadcast_f64x4(0xff, angles4);
  const __m256d magnitude = _mm256_andnot_pd(_mm256_set1_pd(-0.0), angles4);
  // Compared for ≤, false for a NaN: as all_within.
  if (_mm256_movemask_pd(_mm256_cmp_pd(magnitude, _mm256_set1_pd(d::kQuarterPi), _CMP_LE_OQ)) == 0xf) {
    sincos = d::sincos_oct<false>(x);
    return true;
  }
  if (_mm256_movemask_pd(_mm256_cmp_pd(magnitude, _mm256_set1_pd(d::kLimit), _CMP_LE_OQ)) != 0xf)
    return false;
  sincos = d::sincos_oct<true>(x);
  return true;
}

/// sincos3_baseline by sincos3_avx512_lanes (compiled without fused multiply–adds), for the tests that
/// compare the copies. Only where avx512_kernels_available().
void sincos3_avx512(const double* angles, double* sin_out, double* cos_out) noexcept;
#endif

}  // namespace pkm
