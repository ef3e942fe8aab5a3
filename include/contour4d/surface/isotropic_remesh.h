#pragma once
//! \file isotropic_remesh.h
//! \brief Fast isotropic remeshing (Botsch & Kobbelt 2004) on flat arrays: the refinement step of
//! Lim et al. 2014, "Surface Smoothing and Refinement". refine.h's remesh_isotropic calls it with
//! RemeshOptions::engine = Fast: the one-frame surface's rows and the 4D run's frame 0; CGAL's
//! isotropic_remeshing remeshes the bands of one-frame runs without rows (the Delaunay tiling).

#include <array>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Remeshes `mesh` in place towards edges of `edge` mm in `iterations` rounds of: split edges longer
//! than 4/3 edge, collapse edges shorter than 4/5 edge (where no edge longer than 4/3 edge results),
//! flip edges towards valence 6 (4 on boundaries) where the new diagonal is the better one, move each
//! free vertex to the centroid of its neighbours within its tangent plane and project it onto the input
//! surface (the part of it between constrained edges the vertex lies in). Edges listed in `constrained` (vertex pairs, any order) and
//! boundary edges are never split, flipped or collapsed; their vertices and vertices with
//! fixed[v] != 0 never move. Vertices keep their relative order; new ones come last. On return
//! `constrained` lists the constrained edges in the new ids and `fixed` has one entry per vertex
//! (endpoints of constrained edges set). Deterministic (no threads, no hashing order).
//! \return false (mesh unchanged) when the mesh is not an oriented 2-manifold.
bool remesh_isotropic_fast(TriangleMesh& mesh, std::vector<std::array<std::uint32_t, 2>>& constrained,
                           std::vector<char>& fixed, double edge, int iterations);

}  // namespace c4d
