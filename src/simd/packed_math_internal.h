#pragma once
// Square roots and divisions two at a time (SSE2), bit for bit equal to the scalar ones, for the morph's
// hot loops: the relaxation's equilateral pull (motion/morph_relax.cpp) and the RBF's multiquadrics
// (motion/rbf.cpp).
//
// IEEE 754 division and square root are correctly rounded, packed or not, so `sqrt2` and
// `sqrt_of_ratios2` give exactly what two calls of `std::sqrt(a)` and `std::sqrt(a / b)` give: they only
// let the loops issue one instruction for two of them. Without SSE2 they fall back to the scalar calls.
// Internal linkage, as lanes_internal.h: a copy compiled with other instruction sets (motion/simd_avx.cpp)
// could not stand in for these at link time.
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace c4d::detail {
namespace {

// out = {√a0, √a1}.
inline void sqrt2(double a0, double a1, double out[2]) {
#if defined(__SSE2__)
  _mm_storeu_pd(out, _mm_sqrt_pd(_mm_set_pd(a1, a0)));
#else
  out[0] = std::sqrt(a0);
  out[1] = std::sqrt(a1);
#endif
}

// out = {√(a0 / b0), √(a1 / b1)}. A lane with b = 0 gives ∞ or NaN (no trap): callers that skip such
// lanes may pass them.
inline void sqrt_of_ratios2(double a0, double b0, double a1, double b1, double out[2]) {
#if defined(__SSE2__)
  _mm_storeu_pd(out, _mm_sqrt_pd(_mm_div_pd(_mm_set_pd(a1, a0), _mm_set_pd(b1, b0))));
#else
  out[0] = std::sqrt(a0 / b0);
  out[1] = std::sqrt(a1 / b1);
#endif
}

}  // namespace
}  // namespace c4d::detail
