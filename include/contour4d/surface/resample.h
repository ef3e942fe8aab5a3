#pragma once
//! \file resample.h
//! \brief Canonical, evenly spaced contours: the first step of the one-frame surface (Lim et al.
//! 2014, "Reconstruction from Segmented Contour Lines" works on discretised contours). Traced
//! contours are jagged and unevenly spaced; the tiling wants vertices about one target edge apart.

#include <vector>

#include "contour4d/core/vec.h"

namespace c4d {

//! Options for contour resampling.
struct ResampleOptions {
  double edge = 1.0;               //!< target spacing along the contour (mm)
  double corner_angle_deg = 30.0;  //!< input vertices turning more than this are kept exactly
  double tolerance = 0.0;  //!< largest chord deviation from the input on curved arcs (mm); 0: spacing `edge` only
};

//! Index of a canonical start vertex of a closed polygon that depends on its shape only, not on
//! its position, rotation, first vertex or orientation: the vertex farthest from the area
//! centroid (near-ties broken by the following distances in both directions).
int canonical_start(const std::vector<Vec2>& polygon);

//! `polygon` turned counter-clockwise (ccw = true) or clockwise, starting at its canonical vertex.
std::vector<Vec2> canonical_polygon(const std::vector<Vec2>& polygon, bool ccw);

//! Evenly spaced points along a closed polygon (plane coordinates, mm): corners (turning angle
//! over `corner_angle_deg`) and the first vertex are kept, and every arc between two kept
//! vertices is cut into pieces of equal length close to `edge`. With `tolerance` > 0 the spacing
//! shrinks where the contour bends (curvature κ measured at one-edge scale) to √(8·tolerance/κ), at
//! least edge/2, so chords stay within about `tolerance` of the input (points placed at equal steps of
//! the integrated density 1/spacing). The result is the same set of points whichever way the
//! polygon runs; its order follows the input, starting at its first vertex.
std::vector<Vec2> resample_closed(const std::vector<Vec2>& polygon, const ResampleOptions& options = {});

}  // namespace c4d
