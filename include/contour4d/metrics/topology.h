#pragma once
//! \file topology.h
//! \brief Is a triangle mesh a valid closed surface? Holes, non-manifold edges and vertices,
//! orientation, components and genus, self-intersections, degenerate and duplicate elements.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of check_topology.
struct TopologyOptions {
  bool self_intersections = true;  //!< run the (costlier) triangle-triangle intersection test
  //! Counts only, for a stage checking its own meshes on the way: no search for duplicate vertices
  //! and triangles, no orientation flood (`flipped_triangles` 0, `orientable` true) and no
  //! per-component counts (`components` hold their triangle counts only, `genus` is -1).
  bool counts_only = false;
};

//! One connected component (triangles joined through shared edges).
struct ComponentTopology {
  std::size_t vertices = 0;        //!< vertices used by the component
  std::size_t edges = 0;           //!< distinct edges
  std::size_t triangles = 0;       //!< triangles
  std::size_t boundary_loops = 0;  //!< connected chains of boundary edges (holes)
  long euler = 0;                  //!< Euler characteristic χ = V − E + F
  int genus = -1;                  //!< (2 − χ − boundary_loops) / 2; -1 when not a manifold
};

//! Everything check_topology found. A fault is also written in words in `faults`.
struct TopologyReport {
  std::size_t vertices = 0;                   //!< positions
  std::size_t triangles = 0;                  //!< triangles
  std::size_t edges = 0;                      //!< distinct undirected edges
  std::size_t invalid_triangles = 0;          //!< index out of range or repeated in one triangle (ignored below)
  std::size_t degenerate_triangles = 0;       //!< zero area (collinear corners)
  std::size_t duplicate_triangles = 0;        //!< same three vertices as an earlier triangle
  std::size_t duplicate_vertices = 0;         //!< same position as an earlier vertex (bitwise)
  std::size_t unreferenced_vertices = 0;      //!< used by no triangle
  std::size_t boundary_edges = 0;             //!< edges with one triangle: the mesh has a hole
  std::size_t nonmanifold_edges = 0;          //!< edges with more than two triangles
  std::size_t nonmanifold_vertices = 0;       //!< vertices whose triangles form more than one fan
  std::size_t misoriented_edges = 0;          //!< two-triangle edges traversed the same way by both
  std::size_t flipped_triangles = 0;          //!< triangles oriented against the majority of their component
  bool orientable = true;                     //!< false when no consistent orientation exists (Möbius-like)
  std::vector<ComponentTopology> components;  //!< by first triangle index
  int genus = -1;                             //!< sum of the components' genus; -1 when one is undefined
  long euler = 0;                             //!< V − E + F of the whole mesh (used vertices, valid triangles)
  bool self_intersections_checked = false;    //!< the intersection test was run
  std::size_t self_intersections = 0;         //!< pairs of triangles that intersect beyond a shared vertex or edge
  double signed_volume = 0.0;                 //!< enclosed volume (mm³), positive when facing outward
  std::vector<std::string> faults;            //!< one sentence per fault, e.g. "12 boundary edges (a hole)"

  bool closed() const { return boundary_edges == 0; }
  bool edge_manifold() const { return nonmanifold_edges == 0; }
  bool vertex_manifold() const { return nonmanifold_vertices == 0; }
  bool consistently_oriented() const { return misoriented_edges == 0 && orientable; }
  bool outward() const { return signed_volume > 0.0; }
  //! Closed, and a 2-manifold whose neighbouring triangles agree in orientation.
  bool closed_manifold() const { return closed() && edge_manifold() && vertex_manifold() && misoriented_edges == 0; }
  bool ok() const { return faults.empty(); }
};

//! Checks a triangle soup as a closed 2-manifold surface. Faults are reported, never thrown:
//! a mesh with no triangles, invalid, degenerate or duplicate elements, unreferenced vertices,
//! boundary edges, non-manifold edges or vertices, inconsistent orientation, inward orientation
//! (signed volume <= 0 for a closed mesh) and self-intersections. Several components and a
//! genus other than 0 are not faults.
TopologyReport check_topology(const TriangleMesh& mesh, const TopologyOptions& options = {});

//! Number of pairs of triangles that intersect other than in a shared vertex or shared edge
//! (exact predicates; box-intersection prefilter). Zero-area and invalid triangles are skipped.
//! At most `max_pairs_listed` pairs are returned in `pairs` (triangle indices, smaller first).
std::size_t count_self_intersections(const TriangleMesh& mesh,
                                     std::vector<std::pair<std::size_t, std::size_t>>* pairs = nullptr,
                                     std::size_t max_pairs_listed = 8);

//! The same, counting only the pairs in which at least one triangle is flagged in `only` (per
//! triangle): the crossings a local change can have made, at a fraction of the cost.
std::size_t count_self_intersections_of(const TriangleMesh& mesh, const std::vector<char>& only,
                                        std::vector<std::pair<std::size_t, std::size_t>>* pairs = nullptr,
                                        std::size_t max_pairs_listed = 8);

//! True when one of the triangles `these` (indices into `triangles`) intersects another of `these` or
//! one of `others`, by count_self_intersections' rule (exact predicates; zero-area, invalid and
//! non-finite triangles skipped): the test of one vertex's moved ring against the triangles near it,
//! with no tree built (a few dozen box tests).
bool intersects_any(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                    const std::vector<std::uint32_t>& these, const std::vector<std::uint32_t>& others);

}  // namespace c4d
