#pragma once
// Test oracle: the pairs of intersecting triangles by CGAL's own Polygon_mesh_processing::self_intersections,
// against which metrics/topology.h's count_self_intersections (the same rule over vertex indices) is checked.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <utility>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d::testing {

//! Pairs of triangle indices (smaller first, sorted) that intersect; empty when none or when the
//! triangles do not form a 2-manifold surface (CGAL's Surface_mesh refuses them).
inline std::vector<std::array<std::uint32_t, 2>> self_intersecting_pairs(const TriangleMesh& mesh) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SM = CGAL::Surface_mesh<K::Point_3>;
  SM sm;
  std::vector<SM::Vertex_index> vid;
  for (const Vec3& p : mesh.positions) vid.push_back(sm.add_vertex(K::Point_3(p.x, p.y, p.z)));
  std::vector<std::array<std::uint32_t, 2>> out;
  for (const Triangle& t : mesh.triangles)
    if (sm.add_face(vid[t[0]], vid[t[1]], vid[t[2]]) == SM::null_face()) return out;
  std::vector<std::pair<SM::Face_index, SM::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
  for (const auto& [a, b] : pairs) out.push_back({std::min<std::uint32_t>(a, b), std::max<std::uint32_t>(a, b)});
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace c4d::testing
