#pragma once
// Kernels compiled with AVX enabled (core/avx.cpp, motion/simd_avx.cpp): call them only where
// avx_available() says the CPU runs them. Each gives what its SSE2 or scalar form gives, bit for bit.

namespace c4d::detail {

//! Whether this CPU runs the AVX kernels (it has AVX, and the build compiled them).
bool avx_available();

//! The updates of an LDLᵀ chain to the rows below it (sparse_solve.cpp): for each q < below,
//! y[rows[q]] −= columns[t][q] · yv[t] for t = 0, 1, ..., run − 1 in that order, each a multiplication
//! then a subtraction (no fused multiply-add). \pre avx_available().
void ldlt_rows_below_avx(double* y, const int* rows, int below, const double* const* columns, const double* yv, int run);

}  // namespace c4d::detail
