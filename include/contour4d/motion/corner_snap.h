#pragma once
//! \file corner_snap.h
//! \brief Step 3c of the 4D morph (morph.h): a mesh vertex on each sharp corner of a frame's contours, so
//! that the surface passes through the corner instead of cutting it (Lim et al. 2014, "Mesh Conformity":
//! the surface must pass through every input contour).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "contour4d/core/vec.h"

namespace c4d {

//! Options of snap_corners (defaults: what the 4D morph uses).
struct CornerSnapOptions {
  double corner_angle_deg = 30;  //!< a contour point where the contour turns by more than this is a corner
  double reach = 2.0;            //!< candidates lie within this distance (mm) of the corner (the morph: two
                                 //!< median edges)
  std::size_t tries = 3;         //!< candidates tried per corner, nearest first (the morph's retry: 1)
  bool any_vertex = false;       //!< candidates: every vertex (a retry, whose chain vertices are off their
                                 //!< contours), else only the vertices on that contour (`on_line`)
};

//! For each corner of each closed polyline `lines[l]` that has at least one vertex on it (`on_line[l]`), the
//! candidates within `reach` of the corner, nearest first (ties by index), are offered to `harmless(v, corner)`
//! up to `tries` of them; the first it allows moves exactly onto the corner and is marked in `fixed`. Vertices
//! already fixed are passed over. Corners are taken in order (line by line, point by point), so a vertex
//! fixed at one corner is no candidate at the next. Returns the number of vertices moved.
std::size_t snap_corners(std::vector<Vec3>& x, const std::vector<std::vector<Vec3>>& lines,
                         const std::vector<std::vector<std::uint32_t>>& on_line, std::vector<char>& fixed,
                         const std::function<bool(std::uint32_t, Vec3)>& harmless,
                         const CornerSnapOptions& options = {});

}  // namespace c4d
