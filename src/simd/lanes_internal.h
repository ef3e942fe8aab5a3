#pragma once
// SIMD lanes for the morph's hot loops (motion/sweep_lanes_internal.h, motion/rbf_lanes_internal.h): two
// doubles with SSE2, four with AVX (only in code compiled for AVX, motion/simd_avx.cpp), and three
// coordinates with core/vec.h's operations in vec.h's order, so that each lane computes what the one-point
// code computes, bit for bit (IEEE addition, multiplication, division and square root are correctly rounded,
// packed or not; x86-64's baseline and AVX have no fused multiply-add, so the compiler forms none: a build
// for a CPU with FMA needs -ffp-contract=off to keep this).
//
// Everything here has internal linkage: the AVX instantiations are compiled in their own file with AVX
// enabled, the SSE2 ones in the files that use them, and neither may stand in for the other at link time.

#include <cstddef>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace c4d::detail {
namespace {

#if defined(__SSE2__)
// Two lanes (SSE2).
struct Sse2Lanes {
  using V = __m128d;
  static constexpr int n = 2;
  static V set1(double a) { return _mm_set1_pd(a); }
  static V zero() { return _mm_setzero_pd(); }
  static V from(const double* a) { return _mm_set_pd(a[1], a[0]); }
  static void store(double* out, V a) { _mm_storeu_pd(out, a); }
  static V add(V a, V b) { return _mm_add_pd(a, b); }
  static V sub(V a, V b) { return _mm_sub_pd(a, b); }
  static V mul(V a, V b) { return _mm_mul_pd(a, b); }
  static V div(V a, V b) { return _mm_div_pd(a, b); }
  static V sqrt(V a) { return _mm_sqrt_pd(a); }
  static V max(V a, V b) { return _mm_max_pd(a, b); }
  static V greater(V a, V b) { return _mm_cmpgt_pd(a, b); }
  static V and_(V a, V b) { return _mm_and_pd(a, b); }
  static V andnot(V a, V b) { return _mm_andnot_pd(a, b); }
  static V or_(V a, V b) { return _mm_or_pd(a, b); }
  static V mask(const bool* on) { return _mm_castsi128_pd(_mm_set_epi64x(on[1] ? -1 : 0, on[0] ? -1 : 0)); }
};

#if defined(__AVX__)
// Four lanes (AVX).
struct AvxLanes {
  using V = __m256d;
  static constexpr int n = 4;
  static V set1(double a) { return _mm256_set1_pd(a); }
  static V zero() { return _mm256_setzero_pd(); }
  static V from(const double* a) { return _mm256_set_pd(a[3], a[2], a[1], a[0]); }
  static void store(double* out, V a) { _mm256_storeu_pd(out, a); }
  static V add(V a, V b) { return _mm256_add_pd(a, b); }
  static V sub(V a, V b) { return _mm256_sub_pd(a, b); }
  static V mul(V a, V b) { return _mm256_mul_pd(a, b); }
  static V div(V a, V b) { return _mm256_div_pd(a, b); }
  static V sqrt(V a) { return _mm256_sqrt_pd(a); }
  static V max(V a, V b) { return _mm256_max_pd(a, b); }
  static V greater(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }
  static V and_(V a, V b) { return _mm256_and_pd(a, b); }
  static V andnot(V a, V b) { return _mm256_andnot_pd(a, b); }
  static V or_(V a, V b) { return _mm256_or_pd(a, b); }
  static V mask(const bool* on) {
    return _mm256_castsi256_pd(_mm256_set_epi64x(on[3] ? -1 : 0, on[2] ? -1 : 0, on[1] ? -1 : 0, on[0] ? -1 : 0));
  }
};
#endif

// Three coordinates, one vertex per lane, and vec.h's operations on them (same order of operations).
template <class L>
struct Lanes3 {
  using V = typename L::V;
  V x, y, z;

  static Lanes3 zero() { return {L::zero(), L::zero(), L::zero()}; }
  // Lane k from points[k] (P: a point with x, y, z, such as core/vec.h's Vec3).
  template <class P>
  static Lanes3 gather(const P* const* points) {
    double x[L::n], y[L::n], z[L::n];
    for (int k = 0; k < L::n; ++k) {
      x[k] = points[k]->x;
      y[k] = points[k]->y;
      z[k] = points[k]->z;
    }
    return {L::from(x), L::from(y), L::from(z)};
  }
  template <class P>
  void scatter(P* const* points) const {
    double a[L::n], b[L::n], c[L::n];
    L::store(a, x);
    L::store(b, y);
    L::store(c, z);
    for (int k = 0; k < L::n; ++k) *points[k] = {a[k], b[k], c[k]};
  }
  friend Lanes3 operator+(Lanes3 a, Lanes3 b) { return {L::add(a.x, b.x), L::add(a.y, b.y), L::add(a.z, b.z)}; }
  friend Lanes3 operator-(Lanes3 a, Lanes3 b) { return {L::sub(a.x, b.x), L::sub(a.y, b.y), L::sub(a.z, b.z)}; }
  friend Lanes3 operator*(V s, Lanes3 a) { return {L::mul(s, a.x), L::mul(s, a.y), L::mul(s, a.z)}; }
  friend Lanes3 operator/(Lanes3 a, V s) { return {L::div(a.x, s), L::div(a.y, s), L::div(a.z, s)}; }
  // a.x * b.x + a.y * b.y + a.z * b.z, summed left to right.
  friend V dot(Lanes3 a, Lanes3 b) { return L::add(L::add(L::mul(a.x, b.x), L::mul(a.y, b.y)), L::mul(a.z, b.z)); }
  friend Lanes3 cross(Lanes3 a, Lanes3 b) {
    return {L::sub(L::mul(a.y, b.z), L::mul(a.z, b.y)), L::sub(L::mul(a.z, b.x), L::mul(a.x, b.z)),
            L::sub(L::mul(a.x, b.y), L::mul(a.y, b.x))};
  }
};

// mask ? a : b, lane by lane (no arithmetic: exact).
template <class L>
typename L::V pick(typename L::V mask, typename L::V a, typename L::V b) {
  return L::or_(L::and_(mask, a), L::andnot(mask, b));
}
template <class L>
Lanes3<L> pick(typename L::V mask, Lanes3<L> a, Lanes3<L> b) {
  return {pick<L>(mask, a.x, b.x), pick<L>(mask, a.y, b.y), pick<L>(mask, a.z, b.z)};
}

#endif  // __SSE2__

}  // namespace
}  // namespace c4d::detail
