#pragma once
//! \file similarity.h
//! \brief Similarity index of two contours (Lim et al. 2014, "Tree-Based Connectivity", eqs. 5–6):
//! the share of a contour's perimeter that lies inside the other once both are projected on the
//! slice plane, the larger of the two shares.

#include <vector>

#include "contour4d/core/vec.h"

namespace c4d {

//! Fraction (0–1) of the perimeter of closed polygon `a` that lies strictly inside closed polygon
//! `b`, both in the same plane coordinates (mm). Orientation and start point do not matter.
//! Parts of `a` running exactly along an edge of `b` count as inside.
double perimeter_inside(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

//! Eq. 5: max(perimeter_inside(a, b), perimeter_inside(b, a)); symmetric, in [0, 1].
double contour_similarity(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

//! Eq. 6: sum over the contours of slice `a` of their best similarity with a contour of slice `b`.
double slice_similarity(const std::vector<std::vector<Vec2>>& a, const std::vector<std::vector<Vec2>>& b);

//! True when point p lies inside closed polygon `poly` (even–odd rule; boundary points unspecified).
bool point_in_polygon(Vec2 p, const std::vector<Vec2>& poly);

}  // namespace c4d
