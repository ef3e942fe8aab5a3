#pragma once
//! \file refine.h
//! \brief Remeshing to a target edge length for triangle quality (Lim et al. 2014, "Surface
//! Smoothing and Refinement" upsamples the coarse surface; we use CGAL's isotropic remeshing,
//! Botsch & Kobbelt 2004), keeping the input contours as chains of mesh edges.

#include <array>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Which implementation remeshes (the same algorithm and thresholds).
enum class RemeshEngine {
  Fast,  //!< ours on flat arrays (isotropic_remesh.h): a frame about 2× faster
  Cgal,  //!< CGAL::Polygon_mesh_processing::isotropic_remeshing
};

//! Options of remeshing.
struct RemeshOptions {
  double edge = 1.0;              //!< target edge length (mm)
  int iterations = 5;             //!< split/collapse/flip/relax rounds
  bool split_constraints = true;  //!< allow splitting contour edges longer than 4/3 edge (new vertices stay on them)
  RemeshEngine engine = RemeshEngine::Cgal;  //!< Fast (isotropic_remesh.h) is used unless split_constraints (CGAL only)
};

//! Remeshes `mesh` in place. Edges listed in `constrained` (vertex pairs, any order) are kept as
//! polylines: their vertices never move and are never removed; they may only be split. Vertices
//! with fixed[v] != 0 never move. New vertices come last; `fixed` is resized with them (split
//! points of constrained edges are fixed).
//! \pre the mesh is a 2-manifold (with or without boundary).
void remesh_isotropic(TriangleMesh& mesh, std::vector<std::array<std::uint32_t, 2>>& constrained,
                      std::vector<char>& fixed, const RemeshOptions& options = {});

//! Options of flip_edges_delaunay.
struct FlipOptions {
  double max_dihedral_deg = 20.0;  //!< only flip where the two triangles are this close to coplanar (keeps the shape)
  int max_rounds = 20;             //!< passes over all edges at most
  double only_below_deg = 0.0;     //!< > 0: only flip an edge of a triangle with an angle below this, and only where
                                   //!< the flip raises the smallest angle of the pair (slivers left by the repair)
  bool skip_acute = true;          //!< test only the edges beside a right or obtuse angle at a round's start, or
                                   //!< beside a triangle a flip changed since (the same flips; false: test every edge)
};

//! Flips every edge whose two opposite angles sum to more than 180° (the local Delaunay test, on the
//! surface) where the two triangles are nearly coplanar and the flip folds nothing; constrained edges
//! (contours) are never flipped. Removes flat triangles left between three consecutive contour
//! vertices and raises the smallest angles; vertex positions do not change. Returns the flips made.
std::size_t flip_edges_delaunay(TriangleMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& constrained,
                                const FlipOptions& options = {});

//! Flips the chord of every ear, a triangle of three consecutive contour vertices (two constrained edges),
//! so that its middle vertex joins the vertex across the chord, where that vertex is off the contours and the
//! flip folds nothing (and keeps the pair's smallest angle at 15° or raises it). An ear is fine in the frame it
//! was made on but turns flat wherever that contour straightens: a mesh laid onto other frames (the plan of
//! rebuild.h) must have none. Vertex positions do not change. Returns the flips made.
std::size_t flip_ears(TriangleMesh& mesh, const std::vector<std::array<std::uint32_t, 2>>& constrained);

}  // namespace c4d
