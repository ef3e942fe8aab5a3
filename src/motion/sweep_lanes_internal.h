#pragma once
// One relaxation sweep step (morph.cpp, "Tangential relaxation", which keeps the mesh good through the
// cycle: Lim et al. 2014, "4D Morphing of the Heart Model") for several vertices at once, one per SIMD
// lane (SSE2: two, AVX: four): the same operations in the same order as the one-vertex step, so each
// lane's result is the one-vertex result bit for bit (IEEE addition, multiplication, division and square
// root are correctly rounded, packed or not; x86-64's baseline and AVX have no fused multiply-add, so the
// compiler forms none, here or in the one-vertex step: a build for a CPU with FMA needs -ffp-contract=off
// to keep this). The one-vertex step waits on latency (its neighbours' loads, then a division and a
// square root per opposite edge, chained into its sums); independent vertices in one instruction stream
// give the core several chains to overlap. Only the default blend is handled here (springs off,
// equilateral pull on); morph.cpp keeps the one-vertex step for the rest and for vertices left without
// partners.
//
// Everything here has internal linkage: the AVX instantiation is compiled in its own file with AVX
// enabled (sweep_avx.cpp), the SSE2 one in morph.cpp, and neither may stand in for the other at link time.

#include <cstddef>
#include <cstdint>

#include "contour4d/core/vec.h"
#include "sweep_arrays_internal.h"

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
  static V mask(const bool* on) {
    return _mm_castsi128_pd(_mm_set_epi64x(on[1] ? -1 : 0, on[0] ? -1 : 0));
  }
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
  // Lane k from points[k].
  static Lanes3 gather(const Vec3* const* points) {
    double x[L::n], y[L::n], z[L::n];
    for (int k = 0; k < L::n; ++k) {
      x[k] = points[k]->x;
      y[k] = points[k]->y;
      z[k] = points[k]->z;
    }
    return {L::from(x), L::from(y), L::from(z)};
  }
  void scatter(Vec3* const* points) const {
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

// The sweep step of the L::n vertices idx[0..n) (free, with non-empty rings): their new velocities (from
// vel) and positions, as morph.cpp's one-vertex step computes them before sliding.
template <class L>
void sweep_lanes(const SweepArrays& s, const std::size_t* idx, Vec3* vel, Vec3* moved) {
  using V = typename L::V;
  using P = Lanes3<L>;
  constexpr int n = L::n;
  const Vec3* point[n];
  std::size_t ring0[n], rings[n], opp0[n], opps[n];
  bool weighted[n];
  bool any_weighted = false;
  std::size_t most_ring = 0, most_opp = 0;
  for (int k = 0; k < n; ++k) {
    const std::size_t i = idx[k];
    ring0[k] = s.ring_start[i];
    rings[k] = s.ring_start[i + 1] - ring0[k];
    opp0[k] = s.opp_start[i];
    opps[k] = s.opp_start[i + 1] - opp0[k];
    weighted[k] = s.zone[i] != 0;
    any_weighted = any_weighted || weighted[k];
    most_ring = rings[k] > most_ring ? rings[k] : most_ring;
    most_opp = opps[k] > most_opp ? opps[k] : most_opp;
  }
  for (int k = 0; k < n; ++k) point[k] = &s.xs[idx[k]];
  const P xi = P::gather(point);
  for (int k = 0; k < n; ++k) point[k] = &s.ns[idx[k]];
  const P nrm = P::gather(point);
  const V one = L::set1(1.0), zero = L::zero();
  const V weighted_mask = L::mask(weighted);
  const V eight_dev = L::set1(8.0 * s.curv_dev);
  P c = P::zero(), g = P::zero(), mid = P::zero();
  const P sp = P::zero();
  V wsum = zero;
  bool in[n];
  // Umbrella: each lane's ring in its order; a lane past its ring's end keeps its sums (it loads its own
  // vertex, unused).
  for (std::size_t j = 0; j < most_ring; ++j) {
    for (int k = 0; k < n; ++k) {
      in[k] = j < rings[k];
      point[k] = &s.xs[in[k] ? s.ring_index[ring0[k] + j] : idx[k]];
    }
    const P e = P::gather(point) - xi;
    V w = one;
    if (any_weighted) {
      const Vec3* normal[n];
      for (int k = 0; k < n; ++k) normal[k] = &s.ns[point[k] - s.xs];
      const V sign = L::set1(-0.0);
      const V h = L::div(L::add(L::andnot(sign, dot(e, nrm)), L::andnot(sign, dot(e, P::gather(normal)))), eight_dev);
      w = pick<L>(weighted_mask, L::add(one, h), one);
    }
    const V on = L::mask(in);
    wsum = pick<L>(on, L::add(wsum, w), wsum);
    c = pick<L>(on, c + w * e, c);
  }
  // Equilateral pull over each lane's opposite edges, in their order.
  const V tiny = L::set1(1e-300);
  for (std::size_t j = 0; j < most_opp; ++j) {
    const Vec3* pa[n];
    for (int k = 0; k < n; ++k) {
      in[k] = j < opps[k];
      const std::size_t e = 2 * (opp0[k] + j);
      pa[k] = &s.xs[in[k] ? s.opp_index[e] : idx[k]];
      point[k] = &s.xs[in[k] ? s.opp_index[e + 1] : idx[k]];
    }
    const P a = P::gather(pa) - xi, b = P::gather(point) - xi;
    const P e = b - a;
    const V on = L::mask(in);
    mid = pick<L>(on, mid + (a + b), mid);
    const V ee = dot(e, e), ne = dot(nrm, e);
    const V s2 = L::sub(ee, L::mul(ne, ne));
    const V f = L::sqrt(L::div(ee, s2));  // lanes with s2 = 0 (∞ or NaN) are not taken
    g = pick<L>(L::and_(on, L::greater(s2, tiny)), g + f * e, g);
  }
  double counts[n], opp_counts[n];
  for (int k = 0; k < n; ++k) {
    counts[k] = static_cast<double>(rings[k]);
    opp_counts[k] = static_cast<double>(opps[k]);
  }
  const V m = L::from(counts);
  const V inv = L::div(one, m);
  c = pick<L>(weighted_mask, L::div(m, wsum) * c, c);
  // (spring_weight · sp + (1 − spring_weight) · c) · inv with spring_weight = 0, as the one-vertex step.
  P d = inv * (zero * sp + one * c);
  const V no = L::max(one, L::from(opp_counts));
  const P pull = (L::set1(0.5) * mid + L::set1(0.8660254037844386) * cross(nrm, g)) / no;
  d = L::set1(1.0 - s.shape_weight) * d + L::set1(s.shape_weight) * pull;
  d = d - dot(d, nrm) * nrm;
  Vec3* out[n];
  for (int k = 0; k < n; ++k) out[k] = &vel[idx[k]];
  const P v = L::set1(s.beta) * P::gather(out) + L::set1(s.step) * d;
  v.scatter(out);
  for (int k = 0; k < n; ++k) out[k] = &moved[idx[k]];
  (xi + v).scatter(out);
}

#endif  // __SSE2__

}  // namespace
}  // namespace c4d::detail
