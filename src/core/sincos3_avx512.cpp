// The AVX-512 copy of the three-angle sine and cosine out of line, for the tests that compare it with the
// baseline (core/sincos3.hpp). Compiled as its users compile it: without fused multiply–adds.
#include "core/sincos3.hpp"

#if PKM_HAS_WIDE_KERNELS
// GCC fuses multiply–adds in C++ mode where the target has them (AVX-512F does); popped at the end (unity
// builds).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif

namespace pkm {

[[gnu::target("avx512f")]] void sincos3_avx512(const double* angles, double* sin_out,
                                               double* cos_out) noexcept {
  sincos3_detail::Oct lanes;
  if (!sincos3_avx512_lanes(angles, lanes)) return sincos3_detail::library_sincos3(angles, sin_out, cos_out);
  for (int k = 0; k < 3; ++k) {
    sin_out[k] = lanes[k];
    cos_out[k] = lanes[k + 4];
  }
}

}  // namespace pkm

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif
#endif
