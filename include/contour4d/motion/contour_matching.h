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
};

//! Maps the closed polygon `source` (in order; its points are the ones that move) onto the closed
//! polygon `target`, both in the same plane coordinates (mm). Orientation of the inputs does not
//! matter. Cyclic order is preserved, so motion paths do not cross.
//! \pre both polygons have >= 3 points and non-zero length.
ContourMatch match_contour(const std::vector<Vec2>& source, const std::vector<Vec2>& target);

}  // namespace c4d
