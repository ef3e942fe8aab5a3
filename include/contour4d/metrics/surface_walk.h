#pragma once
//! \file surface_walk.h
//! \brief Closest points on a triangle mesh by walking over it: from a starting triangle, greedy
//! descent to the triangle sharing a vertex with the current one whose closest point is nearer, until
//! none is. No tree to build; for queries a fraction of an edge from a known place on the surface (a
//! vertex moved by the remeshing's relaxation or by the small-angle repair's pattern search), where the
//! walk takes one to three steps. It finds a local minimum of the distance: a query far from its start,
//! across a narrow gap from another sheet, may stop on the wrong sheet (use surface_projector.h there).

#include <array>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! The walked surface: its positions and triangles, the patch of each triangle (the walk never
//! leaves the patch it starts in; all 0 for one patch) and, per vertex, its triangles (CSR).
struct SurfaceWalk {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<std::int32_t> patch;           //!< per triangle
  std::vector<std::uint32_t> start, tris;    //!< triangles of vertex v: tris[start[v] .. start[v + 1])
  std::vector<std::array<double, 4>> balls;  //!< per triangle: a ball holding it (centroid, radius)
  //! Per triangle: its plane, unit normal n and offset n·a, and the largest |n·v − offset| of its
  //! corners v as computed (the plane's own rounding, large only on a sliver); all zero for a
  //! degenerate triangle.
  std::vector<std::array<double, 5>> planes;
  //! Optional (add_neighbour_lists): per triangle t, the triangles a walk step from t measures, in its
  //! order: near[near_start[t] .. near_start[t + 1]). Empty: the step finds them around t's corners.
  std::vector<std::uint32_t> near_start, near;
};

//! The walk over `surface` (taken over); `patch` has one entry per triangle, or is empty (one patch).
SurfaceWalk make_surface_walk(TriangleMesh surface, std::vector<std::int32_t> patch = {});

//! Lists, for every triangle, the triangles that a walk step from it measures (those sharing a corner
//! with it, in its patch, each once, in the step's order), so that walks skip the search around the
//! corners: the same answers, bit for bit. Worth it where many walks run over one surface (the
//! remeshing projects every vertex in every round).
void add_neighbour_lists(SurfaceWalk& walk);

//! The closest point to p found by walking from triangle `hint` (a valid triangle index), which is
//! updated to the triangle of the answer: pass it again for the next nearby query.
Vec3 walk_closest(const SurfaceWalk& walk, const Vec3& p, std::int32_t& hint);

//! A triangle of vertex v (its first in the CSR), or −1 when v has none: a start for walk_closest.
std::int32_t walk_start(const SurfaceWalk& walk, std::uint32_t v);

//! Closest point to p on triangle (a, b, c) (Ericson, "Real-Time Collision Detection", 5.1.5); on a
//! degenerate triangle, the closest point of its edges.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace c4d
