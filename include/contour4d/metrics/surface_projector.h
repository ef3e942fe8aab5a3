#pragma once
//! \file surface_projector.h
//! \brief Closest points on a triangle mesh (CGAL AABB tree), with warm starts for repeated queries:
//! the projection of the 4D morph and the surface snap of the small-angle repair; queries near the last
//! answer can instead walk over the surface from it (surface_walk.h), without the tree.
#include <cstdint>
#include <memory>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Closest-point queries on one triangle mesh; the tree is built at the first query that needs it
//! (once). Thread-safe queries.
class SurfaceProjector {
 public:
  explicit SurfaceProjector(const TriangleMesh& surface);
  ~SurfaceProjector();
  SurfaceProjector(const SurfaceProjector&) = delete;
  SurfaceProjector& operator=(const SurfaceProjector&) = delete;
  //! True when the mesh has no triangle of non-zero area (invalid, non-finite and zero-area
  //! triangles are left out); closest() then returns NaN.
  bool empty() const;
  //! Closest point of the surface to p; `normal` (if given) gets the unit normal of its triangle.
  Vec3 closest(Vec3 p, Vec3* normal = nullptr) const;
  //! The same, starting the search from triangle `*hint` (a previous answer for a nearby query;
  //! −1: none) and storing the triangle found there: a warm start for repeated projections.
  Vec3 closest(Vec3 p, Vec3* normal, std::int32_t* hint) const;
  //! The closest point found by walking over the surface from triangle `*hint` (a previous answer
  //! for a query near this one), stored back as for closest(): no tree search. For queries a fraction
  //! of an edge from the last, where the nearest part of the surface is the one around it; a tree
  //! query (closest()) when `*hint` is −1.
  Vec3 walk(Vec3 p, Vec3* normal, std::int32_t* hint) const;
  //! The index in the mesh's triangle list of the triangle a closest() call stored in its hint (−1 for
  //! none).
  std::int32_t mesh_triangle(std::int32_t hint) const;
  //! The hint for the mesh's triangle `triangle` (its index in the mesh's triangle list): −1 where the
  //! projector left it out (zero area, not finite). Hints carry over to a projector of the same
  //! triangles at moved positions this way.
  std::int32_t hint_of(std::int32_t triangle) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace c4d
