#pragma once
//! \file tet_mesh.h
//! \brief Tetrahedral volume meshes that fill a closed triangle surface, keeping its vertices and triangles.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/vec.h"

namespace c4d {

//! A tetrahedron's four node indices, positively oriented: det(b − a, c − a, d − a) > 0.
using Tet = std::array<std::uint32_t, 4>;

//! A tetrahedral mesh in world space (mm). Nodes [0, surface_nodes) are the vertices of the surface it fills,
//! in that surface's order; `boundary` are that surface's triangles (outward, unchanged), each a face of one tet.
struct TetMesh {
  std::vector<Vec3> nodes;                  //!< node positions (mm)
  std::vector<Tet> tets;                    //!< positively oriented tetrahedra
  std::size_t surface_nodes = 0;            //!< the first nodes are the surface's vertices
  std::vector<Triangle> boundary;           //!< the boundary triangles, outward
  std::vector<std::uint32_t> boundary_tet;  //!< the tet each boundary triangle is a face of
};

//! Signed volume of the tetrahedron (a, b, c, d) (mm³): det(b − a, c − a, d − a) / 6.
inline double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return dot(cross(b - a, c - a), d - a) / 6.0;
}

}  // namespace c4d
