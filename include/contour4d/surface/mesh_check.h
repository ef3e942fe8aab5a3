#pragma once
//! \file mesh_check.h
//! \brief Topology checks of a triangle mesh: closed, 2-manifold, consistently and outward oriented,
//! genus, components, self-intersections.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! What check_mesh found.
struct MeshCheck {
  std::size_t boundary_edges = 0;        //!< edges used by one triangle
  std::size_t nonmanifold_edges = 0;     //!< edges used by more than two triangles
  std::size_t misoriented_edges = 0;     //!< edges whose two triangles run them the same way
  std::size_t nonmanifold_vertices = 0;  //!< vertices whose triangles form more than one fan
  std::size_t degenerate_triangles = 0;  //!< repeated vertex or zero area
  std::size_t components = 0;            //!< edge-connected components
  long euler = 0;                        //!< V - E + F over used vertices
  double signed_volume = 0.0;            //!< mm³; positive when outward
  bool self_intersects = false;          //!< only meaningful when checked
  bool closed_manifold() const {
    return boundary_edges == 0 && nonmanifold_edges == 0 && misoriented_edges == 0 && nonmanifold_vertices == 0;
  }
};

//! Checks `mesh`; self-intersections (CGAL PMP) only when `self_intersections` is true.
MeshCheck check_mesh(const TriangleMesh& mesh, bool self_intersections = false);

//! Pairs of triangle indices (smaller first, sorted) that intersect (CGAL PMP); empty when none or
//! when the triangles do not form a 2-manifold surface.
std::vector<std::array<std::uint32_t, 2>> self_intersecting_pairs(const TriangleMesh& mesh);

}  // namespace c4d
