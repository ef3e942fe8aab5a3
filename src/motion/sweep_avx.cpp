// The relaxation sweep's four-vertex step (sweep_lanes_internal.h), compiled with AVX enabled
// (motion/sources.cmake) and called only where the CPU has it (sweep_quad_available). This file must use
// nothing with external linkage that its headers define inline: an AVX copy of such a function could
// replace the plain one everywhere at link time.
#include "sweep_lanes_internal.h"

namespace c4d::detail {

#if defined(__AVX__)
bool sweep_quad_available() { return __builtin_cpu_supports("avx"); }
void sweep_quad(const SweepArrays& s, const std::size_t* idx, Vec3* vel, Vec3* moved) {
  sweep_lanes<AvxLanes>(s, idx, vel, moved);
}
#else
bool sweep_quad_available() { return false; }
void sweep_quad(const SweepArrays&, const std::size_t*, Vec3*, Vec3*) {}
#endif

}  // namespace c4d::detail
