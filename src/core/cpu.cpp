// Whether this CPU runs the library's AVX kernels (core/cpu.h): the build compiled them (C4D_AVX_KERNELS, set
// by cmake/Warnings.cmake where it can enable AVX for one file) and the CPU has AVX.
#include "contour4d/core/cpu.h"

namespace c4d::detail {

bool avx_available() {
#if defined(C4D_AVX_KERNELS)
  return __builtin_cpu_supports("avx");
#else
  return false;
#endif
}

}  // namespace c4d::detail
