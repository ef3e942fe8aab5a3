#pragma once
// The morph's four-lane (AVX) steps, compiled in simd_avx.cpp with AVX enabled: call them only where
// avx_available() (core/cpu.h) says the CPU runs them. Each gives what its two-lane (SSE2) and
// one-point forms give, bit for bit (sweep_lanes_internal.h, rbf_lanes_internal.h).

#include <cstddef>

#include "contour4d/core/cpu.h"
#include "contour4d/core/vec.h"
#include "sweep_arrays_internal.h"

namespace c4d::detail {

//! The relaxation sweep step of the four vertices idx[0..4) (sweep_lanes). \pre avx_available().
void sweep_quad(const SweepArrays& s, const std::size_t* idx, Vec3* vel, Vec3* moved);
//! The RBF sums of four points (rbf_lanes). \pre avx_available().
void rbf_quad(const Vec3* centers, const double* c2, const Vec3* weights, std::size_t n, const Vec3* const* points,
              Vec3* const* out);

}  // namespace c4d::detail
