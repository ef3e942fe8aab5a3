#pragma once
//! \file crease.h
//! \brief Creases along the contours: the angle between neighbouring triangles on the contour lines (edges lying
//! in a slice plane), on the first and last contours (where the caps meet the wall) and between the slices. A
//! surface that is smooth through its contours has the same angles on them as between them.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! The 95th percentiles of the angle between the normals of the two triangles of each edge (degrees).
struct CreaseAngles {
  double on_contours_p95 = 0.0;  //!< edges with both ends in one slice plane (the contour lines)
  double on_ends_p95 = 0.0;      //!< the same on the first and last slice planes only (where caps meet the wall)
  double between_p95 = 0.0;      //!< edges with no end in a slice plane (the wall between the slices)
  std::size_t on_contours = 0;   //!< edges counted in each class
  std::size_t on_ends = 0;
  std::size_t between = 0;
  //! on_contours_p95 / between_p95 (0 when nothing lies between).
  double ratio() const { return between_p95 > 0.0 ? on_contours_p95 / between_p95 : 0.0; }
  //! on_ends_p95 / between_p95 (0 when nothing lies between).
  double ends_ratio() const { return between_p95 > 0.0 ? on_ends_p95 / between_p95 : 0.0; }
};

//! The crease angles of `mesh` against the slice planes of `frame` (planes dot(p, seq.normal) = offset; a vertex
//! lies in a plane within `tolerance_mm`). Edges that are not shared by exactly two triangles, and triangles with an
//! invalid index or no area, are skipped.
CreaseAngles crease_angles(const TriangleMesh& mesh, const Sequence& seq, const Frame& frame,
                           double tolerance_mm = 1e-3);

//! The sharpest edge of a mesh: the largest angle between the normals of two triangles sharing an edge (degrees).
//! Near 180° the surface folds back on itself there, a fin that crosses nothing (the two triangles share the
//! edge) but that no volume mesh can fill.
struct Fold {
  double angle_deg = 0.0;
  std::size_t first = 0, second = 0;  //!< the two triangles (first < second)
};

//! The pairs of triangles that share an edge, each edge once (crease_angles' rule: edges of exactly two triangles
//! with area, valid indices), for sharpest_fold over many positions of one mesh.
std::vector<std::array<std::uint32_t, 2>> neighbour_pairs(const TriangleMesh& mesh);

//! The sharpest fold over `pairs` (neighbour_pairs of the same triangles) at `positions`; a pair whose triangle
//! has no area there is skipped.
Fold sharpest_fold(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                   const std::vector<std::array<std::uint32_t, 2>>& pairs);

//! The sharpest fold of `mesh`.
Fold sharpest_fold(const TriangleMesh& mesh);

}  // namespace c4d
