#pragma once
//! \file angle_repair.h
//! \brief Optimisation-based smoothing of the few vertices around small angles (after Freitag &
//! Ollivier-Gooch 1997): each vertex of a triangle with an angle below a target moves within the
//! surface to the position that maximises the smallest angle of its ring. Connectivity never changes,
//! so it serves both the one-frame surface (Lim et al. 2014, "Surface Smoothing and Refinement") and
//! every frame of the 4D morph (their "quality degrades" relaxation), where flips are not allowed.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of repair_small_angles.
struct AngleRepairOptions {
  double target_deg = 32.0;  //!< vertices of triangles with an angle below this are optimised
  int passes = 4;            //!< passes over the vertices found (the set is found again each pass)
  int steps = 12;            //!< pattern-search steps per vertex (each tries 8 directions, halving on failure)
  double first_step = 0.25;  //!< first step as a fraction of the vertex's mean edge length
};

//! Moves vertex `v` to a candidate position `p` onto the surface (closest point).
using SurfaceSnap = std::function<Vec3(std::uint32_t v, Vec3 p)>;

//! Raises the smallest angles of `triangles` over `positions` by moving, one at a time in index
//! order, each vertex (fixed[v] == 0) of a triangle with an angle below options.target_deg: a
//! pattern search in the vertex's tangent plane, every candidate snapped onto the surface by `snap`,
//! accepted only where the smallest angle of the vertex's triangles grows and none of them turns
//! by more than 60° (no fold; a sliver, smallest angle below 5°, is compared with the vertex normal
//! instead of its own, which is noise). Deterministic (serial). Returns the number of moves made.
std::size_t repair_small_angles(std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                                const std::vector<char>& fixed, const SurfaceSnap& snap,
                                const AngleRepairOptions& options = {});

//! Where triangles intersect (a crowded, folded patch), the free vertices of the intersecting
//! triangles and two rings around them take umbrella steps within the surface (each position
//! snapped by `snap`), up to `rounds` rounds of 10 steps while intersections remain. The (costly)
//! intersection test runs only when some triangle has an angle below 15°; returns the intersecting
//! pairs left then (0: none, or not tested). Deterministic.
std::size_t untangle(std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                     const std::vector<char>& fixed, const SurfaceSnap& snap, int rounds = 4);

//! The smallest angle (degrees) of triangle (a, b, c); 0 when degenerate.
double min_angle_deg(Vec3 a, Vec3 b, Vec3 c);

}  // namespace c4d
