#include "contour4d/core/mesh.h"

namespace c4d {

double signed_volume(const TriangleMesh& mesh) {
  if (mesh.positions.empty()) return 0.0;
  // Tetrahedra from a reference point inside the bounding box keep the sum well conditioned.
  Vec3 ref{};
  for (const Vec3& p : mesh.positions) ref += p;
  ref = ref / static_cast<double>(mesh.positions.size());
  double v = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 a = mesh.positions[t[0]] - ref, b = mesh.positions[t[1]] - ref, c = mesh.positions[t[2]] - ref;
    v += dot(a, cross(b, c));
  }
  return v / 6.0;
}

double surface_area(const TriangleMesh& mesh) {
  double a = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 p = mesh.positions[t[0]], q = mesh.positions[t[1]], r = mesh.positions[t[2]];
    a += 0.5 * norm(cross(q - p, r - p));
  }
  return a;
}

}  // namespace c4d
