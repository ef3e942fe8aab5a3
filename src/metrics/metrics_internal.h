#pragma once
// Private to src/metrics: pieces shared by the public measures and evaluate(), so that evaluate
// builds each frame's AABB trees and sample sets once.

#include <algorithm>
#include <cmath>
#include <numbers>
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

//! The angle between unit vectors a and b (degrees), robust near 0 and 180.
inline double angle_deg(Vec3 a, Vec3 b) { return std::atan2(norm(cross(a, b)), dot(a, b)) * 180.0 / std::numbers::pi; }

//! The value at fraction q of the sorted values (nearest rank). \pre sorted is not empty.
inline double percentile(const std::vector<double>& sorted, double q) {
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::min(sorted.size() - 1, k > 0 ? k - 1 : 0)];
}

//! Arc-length samples of every contour of a frame.
std::vector<Vec3> contour_samples(const Frame& frame, double step);

}  // namespace c4d::metrics_internal
