#pragma once
// One relaxation sweep step (morph_relax.cpp, sweep_one, which keeps the mesh good through the cycle:
// Lim et al. 2014, "4D Morphing of the Heart Model") for several vertices at once, one per SIMD
// lane (simd/lanes_internal.h: two with SSE2, four with AVX), each lane repeating the one-vertex step's
// operations in order, so that its result is the one-vertex result bit for bit. The one-vertex step
// waits on latency (its neighbours' loads, then a division and a square root per opposite edge, chained
// into its sums); independent vertices in one instruction stream give the core several chains to
// overlap. morph_relax.cpp keeps the one-vertex step for vertices left without partners.

#include <cstddef>
#include <cstdint>

#include "contour4d/core/vec.h"
#include "simd/lanes_internal.h"
#include "sweep_arrays_internal.h"

namespace c4d::detail {
namespace {

#if defined(__SSE2__)
// The sweep step of the L::n vertices idx[0..n) (free, with non-empty rings): their new velocities (from
// vel) and positions, as morph_relax.cpp's one-vertex step computes them before sliding.
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
  // (+0 + c) · inv, as the one-vertex step (a −0 becomes +0).
  P d = inv * (P::zero() + c);
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
