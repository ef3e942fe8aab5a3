#pragma once
// What one relaxation sweep step reads (morph_relax.cpp; positions k in the breadth-first order), for the
// one-vertex step there and the several-vertex steps of sweep_lanes_internal.h.

#include <cstddef>
#include <cstdint>

#include "contour4d/core/vec.h"

namespace c4d::detail {

struct SweepArrays {
  const Vec3* xs = nullptr;                 // positions at the sweep's start
  const Vec3* ns = nullptr;                 // unit normals (the round's)
  const std::size_t* ring_start = nullptr;  // each vertex's ring: ring_index[ring_start[k] .. ring_start[k + 1])
  const std::uint32_t* ring_index = nullptr;
  const std::size_t* opp_start = nullptr;  // each vertex's opposite edges: pairs in opp_index
  const std::uint32_t* opp_index = nullptr;
  const char* zone = nullptr;  // saddle-zone weights on (curv_dev > 0 there)
  double curv_dev = 0;         // saddle weights' deviation (mm)
  double shape_weight = 0;     // share of the equilateral pull against the umbrella
  double beta = 0;             // momentum
  double step = 0;             // fraction of the move per sweep
};

}  // namespace c4d::detail
