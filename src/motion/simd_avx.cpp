// The morph's four-lane steps (simd_avx_internal.h): the relaxation sweep (sweep_lanes_internal.h) and the
// RBF sums of eq. 9 (rbf_lanes_internal.h), compiled with AVX enabled (motion/CMakeLists.txt) and called
// only where the CPU has it. This file must use nothing with external linkage that its headers define
// inline: an AVX copy of such a function could replace the plain one everywhere at link time.
#include "simd_avx_internal.h"

#include "rbf_lanes_internal.h"
#include "sweep_lanes_internal.h"

namespace c4d::detail {

#if defined(__AVX__)
void sweep_quad(const SweepArrays& s, const std::size_t* idx, Vec3* vel, Vec3* moved) {
  sweep_lanes<AvxLanes>(s, idx, vel, moved);
}
void rbf_quad(const Vec3* centers, const double* c2, const Vec3* weights, std::size_t n, const Vec3* const* points,
              Vec3* const* out) {
  rbf_lanes<AvxLanes>(centers, c2, weights, n, points, out);
}
#else
void sweep_quad(const SweepArrays&, const std::size_t*, Vec3*, Vec3*) {}
void rbf_quad(const Vec3*, const double*, const Vec3*, std::size_t, const Vec3* const*, Vec3* const*) {}
#endif

}  // namespace c4d::detail
