#pragma once
//! \file contour_matching.h
//! \brief Mapping the points of one contour onto the next frame's contour (Lim et al., "Contour
//! Matching", Fig. 7): intersection points of the two projected contours are break points, and the
//! points between two break points are mapped proportionally by arc length.

#include <vector>

#include "contour4d/core/vec.h"

namespace c4d {

//! How a contour was matched.
enum class MatchMethod {
  BreakPoints,  //!< the contours cross: segments between intersection points mapped proportionally
  Aligned,      //!< no usable crossings (nested or disjoint): arc-length mapping from the best start offset
};

//! Result of matching: one target point per source point, on the target polygon.
struct ContourMatch {
  std::vector<Vec2> targets;
  MatchMethod method = MatchMethod::Aligned;
  int break_points = 0;
  std::vector<Vec2> polygon;  //!< the target polygon, turned to the source's orientation
  std::vector<double> arc;    //!< per target, its arc position along `polygon` (mm, in [0, length))
};

//! The point of the target polygon a fraction f (0..1) of the way, along the polygon, from the
//! target of source point i to the target of source point i+1 (cyclic): where a point that far along
//! the source segment (i, i+1) lands. Unlike the chord between the two targets, it stays on the
//! target polygon where that has corners between them.
Vec2 target_between(const ContourMatch& m, std::size_t i, double f);

//! Maps the closed polygon `source` (in order; its points are the ones that move) onto the closed
//! polygon `target`, both in the same plane coordinates (mm). Orientation of the inputs does not
//! matter. Cyclic order is preserved, so motion paths do not cross.
//! \pre both polygons have >= 3 points and non-zero length.
ContourMatch match_contour(const std::vector<Vec2>& source, const std::vector<Vec2>& target);

}  // namespace c4d
