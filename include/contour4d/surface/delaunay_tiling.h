#pragma once
//! \file delaunay_tiling.h
//! \brief The surface between the contours of two adjacent slices as in Lim et al. 2014,
//! "Reconstruction from Segmented Contour Lines" (after Barequet & Sharir 1996): a constrained
//! Delaunay triangulation of the projected symmetric difference of the two slices' regions, lifted
//! back to the slices, with chordal-axis (CAT) lifting points that break up flat triangles.
//!
//! An alternative to the optimal-band tiling of tiling.h; docs/algorithms/delaunay_tiling.md
//! describes the steps and the choices made where the paper is vague.

#include <cstddef>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/vec.h"

namespace c4d {

//! Settings of tile_slices_delaunay.
struct DelaunayTilingOptions {
  int max_cat_rounds = 4;        //!< rounds of CAT point insertion while flat triangles remain
  bool split_flat_edges = true;  //!< also split inner edges with both ends on one slice (they would touch a cap)
  double crossing_height = 0.5;  //!< height, as a fraction of gap, of the points where the projections meet
  double height_margin =
      0.05;  //!< CAT heights d_lower / (d_lower + d_upper) are mapped into [margin, 1 - margin] · gap
};

//! The band between two slices: new points and triangles over the ids of the input polygons.
struct DelaunayTiling {
  std::vector<Vec3>
      points;  //!< new (CAT) points as (u, v, height above the lower slice); ids start after all polygon vertices
  std::vector<Triangle>
      triangles;  //!< vertex ids: lower polygons' vertices in order (polygon 0 first), then upper polygons', then `points`
  std::vector<std::string> warnings;  //!< anything not handled perfectly
  std::size_t crossing_points =
      0;               //!< points of `points` where lower and upper contours meet in projection (they come first)
  int cat_rounds = 0;  //!< rounds of CAT insertion that added points
  std::size_t flat_triangles =
      0;  //!< triangles with all three vertices at one height left after the last round (0 when all went well)
};

//! \brief Tiles the band between the polygons of two adjacent slices (Lim et al. 2014).
//!
//! lower / upper: closed polygons (no repeated closing point) of the lower slice (height 0) and the upper slice
//! (height gap > 0), in one common 2D frame (both projected on the same plane). Outer contours are counter-clockwise,
//! holes clockwise (seen from above, i.e. looking down the +height axis). All polygons of `lower` and `upper` are one
//! connected component of the slice connectivity (1→1, 1→n, n→1, n→m, rings with holes).
//!
//! Every polygon edge is an edge of exactly one triangle; with the polygons closed by caps (lower
//! cap facing down, upper cap facing up) the band gives a closed, outward-oriented 2-manifold.
//! Polygon vertices are never moved and no point is added on a polygon edge; where lower and upper
//! contours meet in projection (crossings, shared vertices, overlapping edges) a point is added at
//! `crossing_height · gap` and vertical triangles close the contour edge. The result is deterministic.
//! Regions inside a polygon are found by nesting parity, so a polygon given with the wrong
//! orientation still yields an outward band (with a warning).
//! \param gap distance between the slices (mm), > 0
//! \throw InvalidInput when a side is empty, a polygon has fewer than 3 points, a coordinate is not
//! finite, gap ≤ 0, a point repeats within one slice, or the polygons of one slice cross or touch.
DelaunayTiling tile_slices_delaunay(const std::vector<std::vector<Vec2>>& lower,
                                    const std::vector<std::vector<Vec2>>& upper, double gap,
                                    const DelaunayTilingOptions& options = {});

}  // namespace c4d
