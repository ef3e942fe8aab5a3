// The core's AVX kernels (avx_internal.h), compiled with AVX enabled (src/CMakeLists.txt) and called only
// where the CPU has it. This file must use nothing with external linkage that a header defines inline: an
// AVX copy of such a function could replace the plain one everywhere at link time (hence raw pointers).
#include "avx_internal.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace c4d::detail {

#if defined(__AVX__)
bool avx_available() { return __builtin_cpu_supports("avx"); }

void ldlt_rows_below_avx(double* y, const int* rows, int below, const double* const* columns, const double* yv, int run) {
  int q = 0;
  // Sixteen rows at a time: four independent chains of four-lane operations.
  for (; q + 16 <= below; q += 16) {
    __m256d acc[4];
    for (int r = 0; r < 4; ++r) {
      const int* w = rows + q + 4 * r;
      acc[r] = _mm256_set_pd(y[w[3]], y[w[2]], y[w[1]], y[w[0]]);
    }
    for (int t = 0; t < run; ++t) {
      const __m256d v = _mm256_set1_pd(yv[t]);
      const double* c = columns[t] + q;
      acc[0] = _mm256_sub_pd(acc[0], _mm256_mul_pd(_mm256_loadu_pd(c), v));
      acc[1] = _mm256_sub_pd(acc[1], _mm256_mul_pd(_mm256_loadu_pd(c + 4), v));
      acc[2] = _mm256_sub_pd(acc[2], _mm256_mul_pd(_mm256_loadu_pd(c + 8), v));
      acc[3] = _mm256_sub_pd(acc[3], _mm256_mul_pd(_mm256_loadu_pd(c + 12), v));
    }
    for (int r = 0; r < 4; ++r) {
      alignas(32) double out[4];
      _mm256_store_pd(out, acc[r]);
      const int* w = rows + q + 4 * r;
      for (int l = 0; l < 4; ++l) y[w[l]] = out[l];
    }
  }
  for (; q + 4 <= below; q += 4) {
    const int* w = rows + q;
    __m256d a = _mm256_set_pd(y[w[3]], y[w[2]], y[w[1]], y[w[0]]);
    for (int t = 0; t < run; ++t) a = _mm256_sub_pd(a, _mm256_mul_pd(_mm256_loadu_pd(columns[t] + q), _mm256_set1_pd(yv[t])));
    alignas(32) double out[4];
    _mm256_store_pd(out, a);
    for (int l = 0; l < 4; ++l) y[w[l]] = out[l];
  }
  for (; q < below; ++q) {
    double a = y[rows[q]];
    for (int t = 0; t < run; ++t) a -= columns[t][q] * yv[t];
    y[rows[q]] = a;
  }
}
#else
bool avx_available() { return false; }
void ldlt_rows_below_avx(double*, const int*, int, const double* const*, const double*, int) {}
#endif

}  // namespace c4d::detail
