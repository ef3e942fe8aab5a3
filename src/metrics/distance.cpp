// Surface-to-surface distance against a ground truth (Lim et al. 2014, Table 5: mean, max and RMS
// of the distance between the generated and the idealized model, mm).
//
// Both surfaces are sampled deterministically: every vertex, plus the centroids of a regular
// barycentric subdivision of every triangle into n² similar sub-triangles. Each centroid carries
// its sub-triangle's area, so mean and RMS are a midpoint-rule surface integral (independent of
// how unevenly the mesh is triangulated); vertices carry no weight and only sharpen the maximum.
#include "contour4d/metrics/distance.h"

#include <algorithm>
#include <cmath>

#include "contour4d/core/errors.h"
#include "metrics_internal.h"

namespace c4d {
namespace metrics_internal {

DistanceStats weighted_stats(const std::vector<double>& values, const std::vector<double>& weights) {
  DistanceStats s;
  s.samples = values.size();
  if (values.empty()) return s;
  double wsum = 0.0;
  for (double w : weights) wsum += w;
  const bool weighted = weights.size() == values.size() && wsum > 0.0;
  if (!weighted) wsum = static_cast<double>(values.size());
  double sum = 0.0, sq = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double w = weighted ? weights[i] : 1.0;
    sum += w * values[i];
    sq += w * values[i] * values[i];
    s.max = std::max(s.max, values[i]);
  }
  s.mean = sum / wsum;
  s.rms = std::sqrt(sq / wsum);
  double var = 0.0;  // second pass: no cancellation when the spread is small next to the mean
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double w = weighted ? weights[i] : 1.0;
    var += w * (values[i] - s.mean) * (values[i] - s.mean);
  }
  s.std = std::sqrt(var / wsum);
  return s;
}

DirectedSamples measure_samples(const std::vector<SurfaceSample>& samples, const TriangleDistance& target,
                                const SurfaceDistanceOptions& options) {
  DirectedSamples out;
  std::vector<Vec3> points;
  points.reserve(samples.size());
  for (const SurfaceSample& s : samples) points.push_back(s.point);
  out.distance = target.distances(points);
  out.weight.reserve(samples.size());
  if (options.use_slab) out.in_slab.reserve(samples.size());
  for (const SurfaceSample& s : samples) {
    out.weight.push_back(s.area);
    if (options.use_slab) {
      const double h = dot(s.point, options.slab.normal);
      out.in_slab.push_back(h >= options.slab.min_offset && h <= options.slab.max_offset ? 1 : 0);
    }
  }
  return out;
}

namespace {
DistanceStats subset_stats(const DirectedSamples& d, bool slab_only) {
  if (!slab_only) return weighted_stats(d.distance, d.weight);
  std::vector<double> v, w;
  for (std::size_t i = 0; i < d.distance.size(); ++i)
    if (d.in_slab[i]) {
      v.push_back(d.distance[i]);
      w.push_back(d.weight[i]);
    }
  return weighted_stats(v, w);
}
}  // namespace

SurfaceComparison combine(const DirectedSamples& mesh_to_truth, const DirectedSamples& truth_to_mesh,
                          const SurfaceDistanceOptions& options) {
  SurfaceComparison c;
  c.whole.mesh_to_truth = subset_stats(mesh_to_truth, false);
  c.whole.truth_to_mesh = subset_stats(truth_to_mesh, false);
  c.whole.hausdorff = std::max(c.whole.mesh_to_truth.max, c.whole.truth_to_mesh.max);
  if (options.use_slab) {
    c.has_slab = true;
    c.slab.mesh_to_truth = subset_stats(mesh_to_truth, true);
    c.slab.truth_to_mesh = subset_stats(truth_to_mesh, true);
    c.slab.hausdorff = std::max(c.slab.mesh_to_truth.max, c.slab.truth_to_mesh.max);
  }
  return c;
}

}  // namespace metrics_internal

DistanceStats summarize_distances(const std::vector<double>& distances) {
  return metrics_internal::weighted_stats(distances, {});
}

std::vector<SurfaceSample> sample_surface(const TriangleMesh& mesh, const SurfaceSamplingOptions& options) {
  std::vector<SurfaceSample> out;
  out.reserve(mesh.positions.size() + mesh.triangles.size());
  for (const Vec3& p : mesh.positions) out.push_back({p, 0.0});
  const std::size_t nv = mesh.positions.size();
  const int cap = std::max(1, options.max_subdivision);
  for (const Triangle& t : mesh.triangles) {
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) continue;
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const double area = 0.5 * norm(cross(b - a, c - a));
    if (!(area > 0.0) || !std::isfinite(area)) continue;
    const double longest = std::max({distance(a, b), distance(b, c), distance(c, a)});
    int n = 1;
    if (options.spacing > 0.0) n = static_cast<int>(std::clamp(std::ceil(longest / options.spacing), 1.0, double(cap)));
    const double w = area / (double(n) * double(n));
    const Vec3 e1 = (b - a) / double(n), e2 = (c - a) / double(n);
    // Sub-triangle (i, j) "upright" has corners a + i e1 + j e2, +e1, +e2; the "inverted" one
    // next to it (when i + j < n - 1) has corners +e1, +e1+e2, +e2. Centroids at 1/3 and 2/3.
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        out.push_back({a + (i + 1.0 / 3.0) * e1 + (j + 1.0 / 3.0) * e2, w});
        if (i + j < n - 1) out.push_back({a + (i + 2.0 / 3.0) * e1 + (j + 2.0 / 3.0) * e2, w});
      }
  }
  return out;
}

SurfaceComparison compare_surfaces(const TriangleMesh& mesh, const TriangleMesh& truth,
                                   const SurfaceDistanceOptions& options) {
  const metrics_internal::TriangleDistance mesh_tree(mesh), truth_tree(truth);
  if (!mesh_tree.valid() || !truth_tree.valid())
    throw InvalidInput(ErrorCode::BadMesh, {}, std::string(__func__) + ": a mesh has no triangle of non-zero area",
                       "check that both meshes were read correctly");
  const auto forward = metrics_internal::measure_samples(sample_surface(mesh, options.sampling), truth_tree, options);
  const auto backward = metrics_internal::measure_samples(sample_surface(truth, options.sampling), mesh_tree, options);
  return metrics_internal::combine(forward, backward, options);
}

}  // namespace c4d
