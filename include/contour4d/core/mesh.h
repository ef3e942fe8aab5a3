#pragma once
//! \file mesh.h
//! \brief Triangle meshes, and 4D meshes that share one triangle list over all frames.

#include <array>
#include <cstdint>
#include <vector>

#include "contour4d/core/vec.h"

namespace c4d {

using Triangle = std::array<std::uint32_t, 3>;

//! A triangle mesh in world space (mm). Triangles are counter-clockwise seen from outside.
struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

//! A 4D mesh with 1-to-1 vertex correspondence: one triangle list, one position array per frame.
struct MeshSequence {
  std::vector<Triangle> triangles;           //!< shared by every frame
  std::vector<std::vector<Vec3>> positions;  //!< positions[frame][vertex] (mm)
  std::vector<double> times_ms;              //!< time of each frame (ms)

  //! The mesh of one frame (a copy).
  TriangleMesh frame(std::size_t f) const { return {positions.at(f), triangles}; }
};

//! Signed volume (mm³) enclosed by a closed, consistently oriented mesh (divergence theorem);
//! positive when the triangles face outward.
double signed_volume(const TriangleMesh& mesh);

//! Total surface area (mm²).
double surface_area(const TriangleMesh& mesh);

//! The one-ring of every vertex: the vertices sharing an edge with it, sorted, without repeats.
//! Vertices of no triangle get an empty ring.
std::vector<std::vector<std::uint32_t>> vertex_neighbours(std::size_t vertex_count,
                                                          const std::vector<Triangle>& triangles);

}  // namespace c4d
