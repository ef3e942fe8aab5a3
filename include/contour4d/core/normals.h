#pragma once
//! \file normals.h
//! \brief Unit vertex normals of a triangle mesh: area-weighted (the displacement-map bake, the rebuilt
//! frames' landing test, glTF's NORMAL) and after Max 1999, "Weights for computing vertex normals from facet
//! normals" (the all-frames carry).

#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Unit normals, each the normalised sum of its triangles' area vectors; `fallback` for isolated or
//! degenerate vertices.
inline std::vector<Vec3> area_weighted_normals(const std::vector<Vec3>& p, const std::vector<Triangle>& triangles,
                                               Vec3 fallback) {
  std::vector<Vec3> n(p.size(), Vec3{});
  for (const Triangle& t : triangles) {
    const Vec3 c = cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
    for (std::uint32_t v : t) n[v] += c;
  }
  for (Vec3& x : n) {
    const double l = norm(x);
    x = l > 0 ? (1.0 / l) * x : fallback;
  }
  return n;
}

//! Unit normals with Max's weights: each triangle's normal over the product of the squared lengths of its two
//! edges at the vertex. A vertex without non-degenerate triangles keeps a zero vector.
inline std::vector<Vec3> vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> n(mesh.positions.size());
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = mesh.positions[t[k]];
      const Vec3 e1 = mesh.positions[t[(k + 1) % 3]] - p, e2 = mesh.positions[t[(k + 2) % 3]] - p;
      const double w = dot(e1, e1) * dot(e2, e2);
      if (w > 0) n[t[k]] += cross(e1, e2) / w;
    }
  for (Vec3& v : n) v = normalized(v);
  return n;
}

}  // namespace c4d
