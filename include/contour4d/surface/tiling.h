#pragma once
//! \file tiling.h
//! \brief The surface between two connected contours of adjacent slices (Lim et al. 2014,
//! "Reconstruction from Segmented Contour Lines"; tiling after Fuchs, Kedem & Uselton 1977 and the
//! branching of Meyers, Skinner & Sloan 1992), and the bridges that merge several contours into one
//! chain for 1→n and n→1 branching.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Triangulates the band between two closed vertex chains. `lower` lies on the lower slice and
//! `upper` on the upper slice (along the stack normal); both run counter-clockwise seen from
//! above for an outer wall (clockwise for the wall of a hole). Every triangle takes two consecutive
//! vertices of one chain and one of the other (none is flat), each chain edge is used once, and the
//! triangles face outward. Chains may repeat a vertex (bridged chains) but never twice in a row.
//! The tiling minimises the summed length of the spanning edges (dynamic programming, O(n·m)),
//! starting from lower[0] and its nearest upper vertex.
std::vector<Triangle> tile_chains(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                                  const std::vector<Vec3>& positions);

//! tile_chains where a spanning edge may only join entries of the same group (group ≥ 0) or an entry
//! without group (−1): for branching, the vertices of the single contour are grouped by their nearest
//! contour on the other side, bridge vertices have no group. Falls back to the plain tiling when no
//! tiling respects the groups. Group vectors of the wrong size are ignored.
std::vector<Triangle> tile_chains(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                                  const std::vector<Vec3>& positions, const std::vector<int>& lower_group,
                                  const std::vector<int>& upper_group);

//! Intermediate rows of the band between `lower` and `upper` (as in tile_chains), about `spacing` apart
//! across it: the band is cut into round(w / spacing) layers, w the mean length of the optimal tiling's
//! spanning edges (the band's slant width, not the slices' gap), and row r (1 ≤ r < layers) lies at
//! t = r / layers on the spanning edges, resampled at equal arc length into round((1−t)·n + t·m) points,
//! starting on the spanning edge from lower[0]; it runs the same way as the chains. Empty when there
//! would be fewer than 2 layers.
std::vector<std::vector<Vec3>> interpolate_rows(const std::vector<std::uint32_t>& lower,
                                                const std::vector<std::uint32_t>& upper,
                                                const std::vector<Vec3>& positions, double spacing);

//! How interpolate_rows cut one band: the optimal tiling's spanning edges (lower index (i0 + i) mod n,
//! upper (j0 + j) mod m) and each row's point count. Replayed on chains of the same sizes in another
//! frame (rows_on_plan), it gives rows of the same counts: the same mesh, that frame's geometry.
struct RowPlan {
  std::size_t i0 = 0, j0 = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> spans;  //!< (i, j) of each spanning edge, the last one excluded
  int intervals = 0;                                           //!< layers across the band; < 2: no rows
  std::vector<std::size_t> counts;                             //!< points of row r (intervals − 1 rows)
};

//! The plan interpolate_rows follows for these chains (intervals < 2 and no counts when it makes no rows).
RowPlan plan_rows(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                  const std::vector<Vec3>& positions, double spacing);

//! The rows of `plan` between chains of the sizes it was made for, at these positions.
std::vector<std::vector<Vec3>> rows_on_plan(const RowPlan& plan, const std::vector<std::uint32_t>& lower,
                                            const std::vector<std::uint32_t>& upper,
                                            const std::vector<Vec3>& positions);

//! Merges closed chain `b` into closed chain `a` through a bridge between their closest vertices
//! (positions compared as given). `bridge` are the vertex ids of the bridge interior from a's side
//! to b's side (may be empty); they are walked there and back. Returns the merged chain:
//! ..., x, bridge..., y, b loop..., y, reversed bridge..., x, ...
//! `x_at`/`y_at` receive the chosen positions in `a` and `b` when not null.
std::vector<std::uint32_t> bridge_chains(const std::vector<std::uint32_t>& a, std::size_t x_at,
                                         const std::vector<std::uint32_t>& b, std::size_t y_at,
                                         const std::vector<std::uint32_t>& bridge);

}  // namespace c4d
