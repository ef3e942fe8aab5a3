#pragma once
// The frames of the default's all-frames run that are carried rather than rebuilt (reconstruct4d.cpp): those
// whose contours do not fit the plan, and any frame the morph or a carry leaves with crossing triangles.

#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/motion/reconstruct4d.h"

namespace c4d::detail {

// The frames `rep.rebuild.unfit` (empty positions in `out`) carried from the nearest rebuilt frame in the cycle
// onto their own surfaces, with retries; then any of them left crossing carried again from a neighbour
// (recarry_all's rule). Fills rep.carry.frames for them (rep.carry.frames has one entry per frame).
void carry_unfit(const Sequence& seq, MeshSequence& out, const Reconstruct4DOptions& options, Reconstruct4DReport& rep);

// Every frame t ≥ 1 of `out` whose triangles cross (tested where some angle is below 15°, as the untangling
// does), in increasing order, carried again from its neighbour in the cycle that has none (t + 1 first, then
// t − 1) onto its own surface (`surfaces` when given, one per frame, else built with options.surface), the result
// kept when it has fewer crossings (then fewer triangles below 25°, then a larger share of angles in 40–80°).
// Other frames are not touched; rep.carry.frames[t].source names the neighbour used. Deterministic: the frames
// are done in order, each from its neighbours' positions at that point.
void recarry_all(const Sequence& seq, MeshSequence& out, const std::vector<TriangleMesh>* surfaces,
                 const Reconstruct4DOptions& options, Reconstruct4DReport& rep);

}  // namespace c4d::detail
