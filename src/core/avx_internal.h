#pragma once
// Kernels compiled with AVX enabled (core/avx.cpp, motion/simd_avx.cpp): call them only where
// avx_available() says the CPU runs them. Each gives what its SSE2 or scalar form gives, bit for bit.

#include "contour4d/core/cpu.h"

namespace c4d::detail {

//! The updates of an LDLᵀ chain to the rows below it (sparse_solve.cpp): for each q < below,
//! y[rows[q]] −= columns[t][q] · yv[t] for t = 0, 1, ..., run − 1 in that order, each a multiplication
//! then a subtraction (no fused multiply-add). \pre avx_available().
void ldlt_rows_below_avx(double* y, const int* rows, int below, const double* const* columns, const double* yv,
                         int run);

//! y = L⁻ᵀ D⁻¹ L⁻¹ y for three right-hand sides (sparse_solve.cpp's substitute<3>, the same operations in
//! the same order): Y holds row i's three values at Y[4i..4i+2] (Y[4i+3]: any finite value, overwritten),
//! L is compressed column (`counts` null) or not, its column i's entries above the diagonal skipped;
//! d: D, or null for none. \pre avx_available().
void ldlt_substitute3_avx(const int* outer, const int* counts, const int* inner, const double* value, long nnz,
                          const double* d, long n, double* Y);

}  // namespace c4d::detail
