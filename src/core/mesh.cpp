#include "contour4d/core/mesh.h"

#include <algorithm>

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

std::vector<std::vector<std::uint32_t>> vertex_neighbours(std::size_t vertex_count,
                                                          const std::vector<Triangle>& triangles) {
  std::vector<std::vector<std::uint32_t>> ring(vertex_count);
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) {
      ring[t[k]].push_back(t[(k + 1) % 3]);
      ring[t[k]].push_back(t[(k + 2) % 3]);
    }
  for (auto& r : ring) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  return ring;
}

}  // namespace c4d
