// The sparse LDLᵀ factorisation's AVX kernels (ldlt_internal.h), compiled with AVX enabled
// (src/simd/CMakeLists.txt) and called only where the CPU has it. This file must use nothing with external linkage that a header defines inline: an
// AVX copy of such a function could replace the plain one everywhere at link time (hence raw pointers).
#include "ldlt_internal.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace c4d::detail {

#if defined(__AVX__)

void ldlt_rows_below_avx(double* y, const int* rows, int below, const double* const* columns, const double* yv,
                         int run) {
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
    for (int t = 0; t < run; ++t)
      a = _mm256_sub_pd(a, _mm256_mul_pd(_mm256_loadu_pd(columns[t] + q), _mm256_set1_pd(yv[t])));
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

void ldlt_substitute3_avx(const int* outer, const int* counts, const int* inner, const double* value, long nnz,
                          const double* d, long n, double* Y) {
  auto below = [&](long i, long& k0, long& k1) {
    k0 = outer[i];
    k1 = counts ? k0 + counts[i] : outer[i + 1];
    while (k0 < k1 && inner[k0] <= i) ++k0;
  };
  if (nnz > 0)
    for (long i = 0; i < n; ++i) {  // L y = y, column i scattered
      long k0, k1;
      below(i, k0, k1);
      double* yi = Y + 4 * i;
      if (yi[0] != 0.0 && yi[1] != 0.0 && yi[2] != 0.0) {
        const __m256d t = _mm256_loadu_pd(yi);
        for (long k = k0; k < k1; ++k) {
          double* r = Y + 4 * static_cast<long>(inner[k]);
          _mm256_storeu_pd(r, _mm256_sub_pd(_mm256_loadu_pd(r), _mm256_mul_pd(t, _mm256_set1_pd(value[k]))));
        }
      } else {  // Eigen skips a column whose entry is zero (so that −0 stays −0)
        const double t[3] = {yi[0], yi[1], yi[2]};
        for (long k = k0; k < k1; ++k) {
          double* r = Y + 4 * static_cast<long>(inner[k]);
          for (int c = 0; c < 3; ++c)
            if (t[c] != 0.0) r[c] -= t[c] * value[k];
        }
      }
    }
  if (d)
    for (long i = 0; i < n; ++i) {
      const double inv = 1.0 / d[i];
      for (int c = 0; c < 3; ++c) Y[4 * i + c] = inv * Y[4 * i + c];
    }
  if (nnz > 0)
    for (long i = n - 1; i >= 0; --i) {  // Lᵀ y = y, column i gathered
      long k0, k1;
      below(i, k0, k1);
      __m256d t = _mm256_loadu_pd(Y + 4 * i);
      for (long k = k0; k < k1; ++k)
        t = _mm256_sub_pd(
            t, _mm256_mul_pd(_mm256_set1_pd(value[k]), _mm256_loadu_pd(Y + 4 * static_cast<long>(inner[k]))));
      _mm256_storeu_pd(Y + 4 * i, t);
    }
}
#else
void ldlt_substitute3_avx(const int*, const int*, const int*, const double*, long, const double*, long, double*) {}
void ldlt_rows_below_avx(double*, const int*, int, const double* const*, const double*, int) {}
#endif

}  // namespace c4d::detail
