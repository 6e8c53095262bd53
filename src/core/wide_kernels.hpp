#pragma once
// Hot kernels built twice: for the baseline processor the library is compiled for (x86-64: SSE2) and, on
// x86-64 with GCC or Clang, a copy for AVX2 with fused multiply–add, chosen at run time where the processor
// has those instructions. The copy is a function marked PKM_WIDE_KERNEL that calls the baseline code: with
// `flatten`, everything it calls is inlined into it and compiled for AVX2 there, while every function that
// stays out of line (the library's, Eigen's) keeps the baseline instructions, so nothing the rest of the
// program may call needs AVX2. The file holding such a copy is compiled with -ffp-contract=fast
// (cmake/layers.cmake), without which ISO C++ mode fuses no multiply–add; the baseline target has no fused
// instruction, so this changes nothing else there.
//
// Users: the Stewart-platform path tracker (kinematics/stewart_homotopy.cpp) and the elastic model's
// right-hand side (dynamics/elastic_model.cpp).

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define PKM_HAS_WIDE_KERNELS 1
#define PKM_WIDE_KERNEL [[gnu::target("avx2,fma"), gnu::flatten]]
#else
#define PKM_HAS_WIDE_KERNELS 0
#endif

namespace pkm {

/// Whether this processor runs the PKM_WIDE_KERNEL copies (AVX2 and FMA on x86-64); false elsewhere.
bool wide_kernels_available();

/// Whether this processor runs the AVX-512 copies of the kernels that have one (AVX-512F besides AVX2 and
/// FMA); false elsewhere.
bool avx512_kernels_available();

/// Whether the kernels without an option of their own (the elastic right-hand side's) take their wide copy:
/// available and not turned off by a BaselineKernelsOnly in scope.
bool wide_kernels_enabled();

/// While one exists, wide_kernels_enabled() is false: the tests compare the two builds of a kernel. Not for
/// use while another thread runs those kernels.
class BaselineKernelsOnly {
 public:
  BaselineKernelsOnly();
  ~BaselineKernelsOnly();
  BaselineKernelsOnly(const BaselineKernelsOnly&) = delete;
  BaselineKernelsOnly& operator=(const BaselineKernelsOnly&) = delete;
};

}  // namespace pkm
