#pragma once
// What the two slice alignments (slice_alignment.h) share: moving a slice of every frame in its plane.

#include "contour4d/core/stack.h"

namespace c4d::detail {

//! Moves every contour of slice `id`, in every frame, by `shift` (mm).
void move_slice(Sequence& seq, int id, Vec3 shift);

}  // namespace c4d::detail
