// Mesh conformity, Lim et al. 2014, "Mesh Conformity": "measurements at a constant interval
// [0.2 mm] along the input segmented contours ... At each interval point ... its distance to the
// nearest point on the 3D mesh model". The nearest point is exact (AABB tree over the triangles),
// not the nearest vertex, which would overstate the distance by up to half an edge.
#include "contour4d/metrics/conformity.h"

#include "contour4d/core/contour.h"
#include "contour4d/core/errors.h"
#include "metrics_internal.h"

namespace c4d {
namespace metrics_internal {

std::vector<Vec3> contour_samples(const Frame& frame, double step) {
  std::vector<Vec3> out;
  for (const Slice& s : frame.slices)
    for (const Contour& c : s.contours) {
      const std::vector<Vec3> pts = sample_closed_polyline(c.points, step);
      out.insert(out.end(), pts.begin(), pts.end());
    }
  return out;
}

}  // namespace metrics_internal

DistanceStats contour_conformity(const TriangleMesh& mesh, const Frame& frame, const ConformityOptions& options) {
  const metrics_internal::TriangleDistance tree(mesh);
  if (!tree.valid())
    throw InvalidInput(ErrorCode::BadMesh, {}, std::string(__func__) + ": the mesh has no triangle of non-zero area",
                       "check that the mesh was read correctly");
  return summarize_distances(tree.distances(metrics_internal::contour_samples(frame, options.step)));
}

}  // namespace c4d
