#pragma once
//! \file chains.h
//! \brief Frame 0's contour chains (the mesh's copies of the input contours) and their one-to-one
//! partners among another frame's contours (Lim et al. 2014, "Contour Matching": the similarity index,
//! eq. 5, over the threshold both ways).

#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/plane.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! A loop of mesh vertices lying on one slice plane: the mesh's copy of an input contour.
struct Chain {
  int slice = 0;                    //!< slice id
  Plane plane;                      //!< the slice's plane
  std::vector<std::uint32_t> loop;  //!< vertices in order around the loop
};

//! The contour chains of `mesh` (built through the contours of one frame of `seq`): edges with both
//! ends on a slice plane whose two triangles are not both in that plane (so flat caps' interiors are
//! excluded), chained into closed loops. Where a vertex starts two such edges (a cap's ear: a triangle of three
//! contour vertices in the plane, its chord an edge of the dome), the edge whose midpoint lies nearer to the
//! slice's contours in seq.frames[0] is kept.
std::vector<Chain> find_chains(const Sequence& seq, const TriangleMesh& mesh);

//! The contour j that contour i matches one-to-one: i's only partner over `threshold` is j, and j's only
//! partner is i (sim[i][j]: similarity index); −1 when there is none.
int one_to_one_partner(const std::vector<std::vector<double>>& sim, std::size_t i, double threshold);

//! Closest point to q on the closed polyline `loop`. `hint` is the segment found last time (−1: none,
//! then every segment is tried); the search walks from it while a neighbouring segment is closer, so a
//! point that moves a little along the contour costs a few segment tests. `hint` gets the segment found.
Vec3 closest_on_loop(const std::vector<Vec3>& loop, Vec3 q, std::int32_t& hint);

}  // namespace c4d
