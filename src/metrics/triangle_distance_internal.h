#pragma once
// Private to src/metrics: exact point-to-surface distance (a SurfaceProjector underneath) behind
// the small interface the metrics use.

#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/metrics/surface_projector.h"

namespace c4d::metrics_internal {

//! Distance from points to the triangles of one mesh: an AABB tree built once, queried many times.
//! Zero-area triangles are left out of the tree (their points lie on their neighbours' edges).
class TriangleDistance {
 public:
  explicit TriangleDistance(const TriangleMesh& mesh) : surface_(mesh) {}

  //! False when the mesh has no triangle of non-zero area (every distance is then +inf).
  bool valid() const;
  //! Euclidean distance (mm) from p to the closest point of the surface.
  double distance(Vec3 p) const;
  //! distance() for every point, in order.
  std::vector<double> distances(const std::vector<Vec3>& points) const;
  //! The closest-point queries underneath (for normals against the same surface).
  const SurfaceProjector& surface() const { return surface_; }

 private:
  SurfaceProjector surface_;
};

}  // namespace c4d::metrics_internal
