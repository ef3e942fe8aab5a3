#pragma once
// The sparse LDLᵀ factorisation's SIMD kernels, called by core/sparse_solve.cpp: the AVX ones (ldlt_avx.cpp,
// compiled with AVX enabled) only where core/cpu.h's avx_available() says the CPU runs them, the SSE2 one
// (inline here, internal linkage) elsewhere. Each gives what its scalar form gives, bit for bit.

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace c4d::detail {

//! The updates of an LDLᵀ chain to the rows below it (core/sparse_solve.cpp): for each q < below,
//! y[rows[q]] −= columns[t][q] · yv[t] for t = 0, 1, ..., run − 1 in that order, each a multiplication
//! then a subtraction (no fused multiply-add). \pre the CPU runs AVX.
void ldlt_rows_below_avx(double* y, const int* rows, int below, const double* const* columns, const double* yv,
                         int run);

//! y = L⁻ᵀ D⁻¹ L⁻¹ y for three right-hand sides (core/sparse_solve.cpp's substitute<3>, the same operations in
//! the same order): Y holds row i's three values at Y[4i..4i+2] (Y[4i+3]: any finite value, overwritten),
//! L is compressed column (`counts` null) or not, its column i's entries above the diagonal skipped;
//! d: D, or null for none. \pre the CPU runs AVX.
void ldlt_substitute3_avx(const int* outer, const int* counts, const int* inner, const double* value, long nnz,
                          const double* d, long n, double* Y);

namespace {

//! ldlt_rows_below_avx's updates for the rows q < below rounded down to a multiple of eight, two rows per
//! SSE2 instruction in four independent chains, each lane a row's own chain of operations. Returns the
//! number of rows done (0 without SSE2); the caller's scalar loop does the rest.
inline int ldlt_rows_below_sse2(double* y, const int* rows, int below, const double* const* columns, const double* yv,
                                int run) {
  int q = 0;
#if defined(__SSE2__)
  for (; q + 8 <= below; q += 8) {
    __m128d acc[4];
    for (int r = 0; r < 4; ++r) acc[r] = _mm_set_pd(y[rows[q + 2 * r + 1]], y[rows[q + 2 * r]]);
    for (int t = 0; t < run; ++t) {
      const __m128d v = _mm_set1_pd(yv[t]);
      const double* c = columns[t] + q;
      acc[0] = _mm_sub_pd(acc[0], _mm_mul_pd(_mm_loadu_pd(c), v));
      acc[1] = _mm_sub_pd(acc[1], _mm_mul_pd(_mm_loadu_pd(c + 2), v));
      acc[2] = _mm_sub_pd(acc[2], _mm_mul_pd(_mm_loadu_pd(c + 4), v));
      acc[3] = _mm_sub_pd(acc[3], _mm_mul_pd(_mm_loadu_pd(c + 6), v));
    }
    for (int r = 0; r < 4; ++r) {
      y[rows[q + 2 * r]] = _mm_cvtsd_f64(acc[r]);
      y[rows[q + 2 * r + 1]] = _mm_cvtsd_f64(_mm_unpackhi_pd(acc[r], acc[r]));
    }
  }
#endif
  return q;
}

}  // namespace

}  // namespace c4d::detail
