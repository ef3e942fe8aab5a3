#pragma once
//! \file cpu.h
//! \brief What the CPU runs: the library's AVX kernels are called only where it has AVX (each gives what
//! its SSE2 or scalar form gives, bit for bit, so the answer changes speed, never results).

namespace c4d::detail {

//! Whether this CPU runs the AVX kernels (it has AVX, and the build compiled them).
bool avx_available();

}  // namespace c4d::detail
