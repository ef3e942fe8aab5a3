#pragma once
// Private to src/metrics: pieces shared by the public measures and evaluate(), so that evaluate
// builds each frame's AABB trees and sample sets once.

#include <vector>

#include "contour4d/core/stack.h"
#include "contour4d/metrics/distance.h"
#include "triangle_distance_internal.h"

namespace c4d::metrics_internal {

//! Weighted statistics: mean, rms and std use `weights` (when their sum is > 0, else every value
//! counts once); max and samples use every value.
DistanceStats weighted_stats(const std::vector<double>& values, const std::vector<double>& weights);

//! Distances from surface samples to a tree, with slab membership of each sample.
struct DirectedSamples {
  std::vector<double> distance;  //!< per sample (mm)
  std::vector<double> weight;    //!< per sample (mm²)
  std::vector<char> in_slab;     //!< per sample, when a slab is used
};

//! Measures `samples` against `target`.
DirectedSamples measure_samples(const std::vector<SurfaceSample>& samples, const TriangleDistance& target,
                                const SurfaceDistanceOptions& options);

//! Combines both directions into whole-surface and slab statistics.
SurfaceComparison combine(const DirectedSamples& mesh_to_truth, const DirectedSamples& truth_to_mesh,
                          const SurfaceDistanceOptions& options);

//! Arc-length samples of every contour of a frame.
std::vector<Vec3> contour_samples(const Frame& frame, double step);

}  // namespace c4d::metrics_internal
