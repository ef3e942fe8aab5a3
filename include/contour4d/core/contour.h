#pragma once
//! \file contour.h
//! \brief A contour: one closed planar polygon drawn on one slice (Lim et al., "Model Definition", eq. 1).

#include <string>
#include <vector>

#include "contour4d/core/vec.h"

namespace c4d {

//! A closed planar polygon in world space (mm). The closing edge from the last point back to the
//! first is implicit (the first point is not repeated). Either orientation is accepted on input.
struct Contour {
  std::string label;         //!< structure name, e.g. "lv-endo"; empty when the input gave none
  int slice = 0;             //!< slice id: the same plane in every frame
  std::vector<Vec3> points;  //!< vertices in order, world coordinates (mm)
};

//! Signed area (mm²) of a polygon in plane coordinates; positive when counter-clockwise.
double signed_area(const std::vector<Vec2>& polygon);

//! Perimeter (mm) of a closed polygon, the closing edge included.
double perimeter(const std::vector<Vec3>& polygon);

//! Points every `step` mm along a closed polygon, starting at its first vertex (arc-length
//! sampling; the vertices themselves are not necessarily included). Used by conformity
//! measurements (Lim et al., "Mesh Conformity": every 0.2 mm).
std::vector<Vec3> sample_closed_polyline(const std::vector<Vec3>& polygon, double step);

//! The point of the polyline `poly` closest to p (the first such point along it; closed: the last point
//! joins the first); p when `poly` is empty.
Vec2 closest_on_polyline(Vec2 p, const std::vector<Vec2>& poly, bool closed = true);

//! Distance (mm) from p to the polyline `poly` (closed: the last point joins the first); infinity when empty.
double polyline_distance(Vec2 p, const std::vector<Vec2>& poly, bool closed = true);

//! True when the closed polygon has two non-adjacent edges that touch or cross (O(n log n)
//! sweep is not needed for our sizes: O(n²) with a bounding-box prefilter).
bool is_self_intersecting(const std::vector<Vec2>& polygon);

}  // namespace c4d
