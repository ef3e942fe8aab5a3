#pragma once
// What the two slice alignments (slice_alignment.h) share: moving a slice of every frame in its plane, and the
// robust statistics of their fits.

#include <vector>

#include "contour4d/core/stack.h"

namespace c4d::detail {

//! Moves every contour of slice `id`, in every frame, by `shift` (mm).
void move_slice(Sequence& seq, int id, Vec3 shift);

//! A median absolute residual times this: the normal law's σ.
constexpr double kMadToSigma = 1.4826;

//! The median of `v` (the upper one of an even count); `v` not empty.
double median(std::vector<double> v);

//! Tukey's bisquare weight of a residual r at scale σ: (1 − z²)² for z = r / (4.685 σ) < 1, else 0.
double tukey_weight(double r, double sigma);

}  // namespace c4d::detail
