#pragma once
//! \file capping.h
//! \brief Caps that close the top-most and bottom-most contours and branch ends (Lim et al. 2014,
//! "Reconstruction from Segmented Contour Lines": the interior of end slices is triangulated, and
//! chordal-axis points pulled out of the plane give a rounded tip).

#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! How the ends of a structure are closed.
enum class CapStyle {
  Rounded,  //!< a dome: interior points lifted with the distance to the contour (circular profile)
  Flat,     //!< a flat lid in the slice plane
  Open,     //!< no cap: the mesh keeps a hole there (valve planes, CFD inlets)
};

//! Options of a cap.
struct CapOptions {
  double edge = 1.0;     //!< target edge length of the cap's interior triangles (mm)
  double height = 2.5;   //!< dome height (mm), Rounded only; clipped to the region's half width
};

//! A planar cap in plane coordinates plus a height per point.
struct CapMesh {
  std::vector<Vec2> points;                       //!< the loops' points first (in input order), then interior points
  std::vector<double> height;                     //!< lift of each point along the cap direction (mm); 0 on the loops
  std::vector<Triangle> triangles;                //!< counter-clockwise in the plane
};

//! Triangulates the region bounded by `loops` (an outer loop and its holes; even–odd nesting) with
//! a constrained Delaunay triangulation plus interior points about `edge` apart (CGAL's 2D
//! Delaunay mesher), never splitting a loop edge, and lifts the interior for CapStyle::Rounded.
//! Loop point k of loop l has index (size of loops 0..l-1) + k in the result.
CapMesh triangulate_cap(const std::vector<std::vector<Vec2>>& loops, CapStyle style, const CapOptions& options = {});

}  // namespace c4d
