#pragma once
//! \file contour_smoothing.h
//! \brief Contours traced on images are jagged at the pixel scale; a surface through every traced point creases
//! along every contour. Each contour is replaced by the smoothest closed curve (a periodic smoothing spline) that
//! stays within a tolerance of it, about half a pixel, with its area kept; exact contours (tolerance 0) are left
//! as they are.

#include <vector>

#include "contour4d/core/stack.h"

namespace c4d {

//! How one contour was smoothed, for report.json.
struct ContourSmoothing {
  int frame = 0;               //!< 0-based frame
  int slice = 0;               //!< slice id
  int contour = 0;             //!< 0-based index of the contour within its slice
  double stiffness = 0.0;      //!< λ of the smoothing spline (0: left as it was)
  double moved_max_mm = 0.0;   //!< largest distance between the input and the smoothed contour, both ways (mm)
  double moved_mean_mm = 0.0;  //!< mean distance of the input points to the smoothed contour (mm)
};

//! The smoothing spline of a closed polygon within `tolerance_mm`: the points x minimising
//! Σ|x_i − p_i|² + λ Σ|x_{i−1} − 2x_i + x_{i+1}|² for the largest λ (searched on a logarithmic scale) whose
//! result, moved along its normals to keep the polygon's area, stays simple and within `tolerance_mm` of the
//! input both ways (each input point to the result, each result point to the input). Returns the input when
//! tolerance_mm <= 0, when it has fewer than 5 points or when no λ qualifies. `stiffness` (optional) receives λ.
std::vector<Vec2> smooth_polygon(const std::vector<Vec2>& polygon, double tolerance_mm, double* stiffness = nullptr);

//! Smooths every contour of `seq` in its slice plane (smooth_polygon in the stack's u, v coordinates; each point
//! keeps its distance from the plane) and lists what was done, by frame, slice and contour.
std::vector<ContourSmoothing> smooth_contours(Sequence& seq, double tolerance_mm);

}  // namespace c4d
