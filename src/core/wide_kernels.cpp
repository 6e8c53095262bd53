#include "core/wide_kernels.hpp"

#include <atomic>

namespace pkm {
namespace {

std::atomic<int> baseline_only_scopes{0};

}  // namespace

bool wide_kernels_available() {
#if PKM_HAS_WIDE_KERNELS
  // __builtin_cpu_init: the answer may be asked for while the program's constructors run (kernels that
  // decide once, at load).
  static const bool available =
      (__builtin_cpu_init(), __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"));
  return available;
#else
  return false;
#endif
}

bool avx512_kernels_available() {
#if PKM_HAS_WIDE_KERNELS
  static const bool available = wide_kernels_available() && __builtin_cpu_supports("avx512f");
  return available;
#else
  return false;
#endif
}

bool wide_kernels_enabled() {
  return wide_kernels_available() && baseline_only_scopes.load(std::memory_order_relaxed) == 0;
}

BaselineKernelsOnly::BaselineKernelsOnly() {
  baseline_only_scopes.fetch_add(1);
}
BaselineKernelsOnly::~BaselineKernelsOnly() {
  baseline_only_scopes.fetch_sub(1);
}

}  // namespace pkm
