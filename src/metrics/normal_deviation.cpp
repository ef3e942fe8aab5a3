// Facet normals against a reference surface (normal_deviation.h): the shading check beside the distances
// of distance.h, for a carried frame against its own one-frame surface and a decoded compact model against
// the exact meshes.
#include "contour4d/metrics/normal_deviation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include <tbb/parallel_for.h>

#include "contour4d/core/errors.h"
#include "metrics_internal.h"

namespace c4d {

namespace {

using metrics_internal::angle_deg;
using metrics_internal::percentile;

}  // namespace

NormalDeviation normal_deviation(const TriangleMesh& mesh, const TriangleMesh& reference) {
  return normal_deviation(mesh, SurfaceProjector(reference));
}

NormalDeviation normal_deviation(const TriangleMesh& mesh, const SurfaceProjector& projector) {
  if (projector.empty())
    throw InvalidInput(ErrorCode::BadMesh, {}, "the reference surface has no triangle of non-zero area",
                       "check that the reference meshes were read correctly");
  const std::size_t n = mesh.triangles.size();
  std::vector<double> angle(n, -1.0);  // -1: a zero-area triangle, left out
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    const Triangle& t = mesh.triangles[i];
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const Vec3 normal = cross(b - a, c - a);
    const double area2 = norm(normal);
    if (!(area2 > 0.0)) return;
    Vec3 reference_normal;
    projector.closest((1.0 / 3.0) * (a + b + c), &reference_normal);
    angle[i] = angle_deg((1.0 / area2) * normal, reference_normal);
  });
  std::vector<double> sorted;
  sorted.reserve(n);
  for (double x : angle)
    if (x >= 0.0) sorted.push_back(x);
  NormalDeviation out;
  out.triangles = sorted.size();
  if (sorted.empty()) return out;
  std::sort(sorted.begin(), sorted.end());
  out.mean_deg = std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(sorted.size());
  out.median_deg = percentile(sorted, 0.5);
  out.p99_deg = percentile(sorted, 0.99);
  out.max_deg = sorted.back();
  return out;
}

}  // namespace c4d
