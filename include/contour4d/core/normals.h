#pragma once
//! \file normals.h
//! \brief Area-weighted unit vertex normals of a triangle mesh: the direction of the compact model's scalar
//! corrections (computed alike when encoding and decoding), the displacement-map bake and glTF's NORMAL.

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

}  // namespace c4d
