#pragma once
// The radial basis function interpolant of eq. 9 (Lim et al. 2014, "4D Morphing of the Heart Model";
// rbf.cpp) at several points at once, one point per SIMD lane (simd/lanes_internal.h: two with SSE2,
// four with AVX): each lane sums the Hardy multiquadrics of the centres in their order, as
// RbfDeformer::apply(Vec3) does, so its sum is that one's bit for bit. One point at a time, the sum is a
// chain of dependent additions behind a square root per centre; several points keep several chains busy.

#include <cstddef>

#include "contour4d/core/vec.h"
#include "simd/lanes_internal.h"

namespace c4d::detail {
namespace {

#if defined(__SSE2__)
// points[k] + Σ_j √(|points[k] − centers[j]|² + c2[j]) · weights[j] (j = 0 … n − 1 in order) into *out[k],
// for the L::n points.
template <class L>
void rbf_lanes(const Vec3* centers, const double* c2, const Vec3* weights, std::size_t n, const Vec3* const* points,
               Vec3* const* out) {
  using P = Lanes3<L>;
  const P p = P::gather(points);
  P sum = p;
  for (std::size_t j = 0; j < n; ++j) {
    const P c{L::set1(centers[j].x), L::set1(centers[j].y), L::set1(centers[j].z)};
    const P d = p - c;
    const typename L::V r = L::sqrt(L::add(dot(d, d), L::set1(c2[j])));
    sum = sum + r * P{L::set1(weights[j].x), L::set1(weights[j].y), L::set1(weights[j].z)};
  }
  sum.scatter(out);
}
#endif  // __SSE2__

}  // namespace
}  // namespace c4d::detail
