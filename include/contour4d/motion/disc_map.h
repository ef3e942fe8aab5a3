#pragma once
//! \file disc_map.h
//! \brief One disc of a mesh laid onto another disc with the same border curve, one-to-one: both flattened
//! onto the unit disc by Floater's mean-value parametrization (M. S. Floater, "Mean value coordinates",
//! CAGD 20, 2003), their borders by arc length along that shared curve, then each vertex of the first
//! lifted from its place in the second's flattening. A convex border makes each flattening an embedding
//! (Floater 2003, Tutte's theorem), so the composed map folds nothing: a dome that retreated through a slice
//! plane (Lim et al. 2014's vanishing contour) lands on the frame's own dome and nowhere else.

#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/vec.h"

namespace c4d {

//! A disc of a mesh: its triangles and its border loop in order (vertex indices into the mesh's positions).
struct Disc {
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> border;
};

//! Whether `triangles` form a disc: one border loop and Euler characteristic 1.
bool is_disc(const std::vector<Triangle>& triangles);

//! The part of `mesh` beyond the closed planar `contour` (`dir` points from its plane into that part): the
//! triangles with every vertex on or beyond the plane (within 1e-5 mm), the connected part whose border lies on
//! the contour (within 1e-3 mm), as a disc with its border loop. Empty when there is no such disc. On a frame's
//! own one-frame surface and its last contour: the dome that closes the end there.
Disc disc_beyond(const TriangleMesh& mesh, const std::vector<Vec3>& contour, Vec3 dir);

//! The disc's vertices on the unit disc (the others of `x` at (0, 0)): the border vertex border[k] at angle
//! 2π·turns[k] on the unit circle, each inner vertex at the mean-value average of its neighbours (positive
//! weights from x's angles). The turns go once around the circle in the border's order, either way.
std::vector<Vec2> flatten_disc(const std::vector<Vec3>& x, const Disc& disc, const std::vector<double>& turns);

//! The points of the disc (`x`, flattened to `uv` by flatten_disc) at the flat places `where`: the triangle
//! holding each (the nearest one when a place falls just outside), by barycentric coordinates.
std::vector<Vec3> lift_from_disc(const std::vector<Vec2>& where, const std::vector<Vec3>& x, const Disc& disc,
                                 const std::vector<Vec2>& uv);

//! The arc-length position of each of `points` along the closed polyline `loop` (as a share of its length,
//! in [0, 1), from loop[0] in the loop's order): where the closest point of the loop lies.
std::vector<double> turns_along(const std::vector<Vec3>& loop, const std::vector<Vec3>& points);

}  // namespace c4d
