#pragma once
//! \file capping.h
//! \brief Caps that close the top-most and bottom-most contours and branch ends (Lim et al. 2014,
//! "Reconstruction from Segmented Contour Lines": the interior of end slices is triangulated, and
//! chordal-axis points pulled out of the plane give a rounded tip).

#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! How the ends of a structure are closed.
enum class CapStyle {
  Rounded,  //!< a dome: interior points lifted with the distance to the contour (circular profile)
  Flat,     //!< a flat lid in the slice plane
  Open,     //!< no cap: the mesh keeps a hole there (valve planes, CFD inlets)
};

//! Options of a cap.
struct CapOptions {
  double edge = 1.0;        //!< target edge length of the cap's interior triangles (mm)
  double height = 2.5;      //!< dome height (mm), Rounded only; clipped to the region's half width
  double near_edges = 2.0;  //!< interior triangles within this many edges of the loops are at most `edge` long
  double ramp_edges = 5.0;  //!< beyond this many edges from the loops the bound is far_scale × edge (linear in between)
  double far_scale = 3.0;   //!< size bound far from the loops, in edges (≤ 1 or not finite: uniform `edge`). A
                            //!< coarser interior has fewer unknowns for the fairing;
                            //!< the final remeshing restores `edge`. reconstruct_frame uses 1 on rings, whose faired
                            //!< dome sets their volume
  double uniform_scale = 1.0;  //!< size bound of a uniform interior (far_scale ≤ 1), in edges. CGAL's bound caps
                               //!< each triangle's longest edge, so the mean edge comes out near 0.7 of it: √2
                               //!< gives a mean near `edge`. reconstruct_frame uses √2 on rings (about half the
                               //!< points per cap)
};

//! A planar cap in plane coordinates plus a height per point.
struct CapMesh {
  std::vector<Vec2> points;         //!< the loops' points first (in input order), then interior points
  std::vector<double> height;       //!< lift of each point along the cap direction (mm); 0 on the loops
  std::vector<Triangle> triangles;  //!< counter-clockwise in the plane
};

//! Triangulates the region bounded by `loops` (an outer loop and its holes; even–odd nesting) with
//! a constrained Delaunay triangulation plus interior points (CGAL's 2D Delaunay mesher: about `edge`
//! apart next to the loops, up to far_scale × edge apart far from them), never splitting a loop edge,
//! and lifts the interior for CapStyle::Rounded.
//! Loop point k of loop l has index (size of loops 0..l-1) + k in the result.
CapMesh triangulate_cap(const std::vector<std::vector<Vec2>>& loops, CapStyle style, const CapOptions& options = {});

//! Where a cap sits, in a frame whose slice planes are z = const: the end contour's plane z0, the
//! side the cap bulges to (dir = +1 above, −1 below) and its greatest height (mm).
struct CapFrame {
  double z0 = 0.0;
  double dir = 1.0;
  double height = 0.0;
};

//! Volume (mm³) between a cap's plane and its triangles (exact for a closed rim on the plane: the
//! sum of each triangle's signed projected area times its mean height, heights below the plane counted as 0).
double cap_volume(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles, const CapFrame& frame);

//! The volume a cap over an end contour of area `area` should hold when the section area changes
//! linearly past the end, as it does from the neighbouring slice (area `neighbour_area`, `spacing`
//! away): ∫₀ʰ clamp(area + (area − neighbour_area)·d/spacing, 0, area) dd, then at most
//! `max_fill` of the prism area·height. Ends whose sections hold their size (a tube cut across) get
//! a full, flat-topped dome; ends that close fast (an apex) a low one, which a faired dome usually
//! holds already.
double extrapolated_cap_volume(double area, double neighbour_area, double spacing, double height, double max_fill);

//! Lifts a faired cap to `target` volume without moving its rim or widening it: every height u ≥ 0
//! becomes u + c·u²/height, c ≥ 0 solved in closed form (the volume is linear in c). The lift's slope
//! is 1 at the rim, so the cap leaves the end contour with the slope the fairing gave it (the wall's);
//! the extra volume goes to its middle, which rises towards where the sections' trend puts the end.
//! Vertices at height 0 (the rim) stay. Returns c (0 when the cap already holds `target`).
double fill_cap(std::vector<Vec3>& positions, const std::vector<Triangle>& triangles, const CapFrame& frame,
                double target);

//! The wall between an end contour (the one under a cap) and the contours it connects to on the
//! neighbouring slice, in a frame whose slice planes are z = const.
struct EndBand {
  std::vector<Triangle> triangles;     //!< the wall's triangles (outward)
  std::vector<std::uint32_t> movable;  //!< its free vertices (not on a contour)
  double z_end = 0.0, z_ref = 0.0;     //!< planes of the end contour and of the neighbouring slice
  Vec2 c_end{}, c_ref{};               //!< area centroids of the two sides' contours
  double area_end = 0.0;               //!< area enclosed by the end contour(s) (mm²)
};

//! Volume (mm³) enclosed by the wall and the two slice planes. `orientation` is +1 when the mesh's
//! triangles face outward in this frame, −1 otherwise.
double end_band_volume(const std::vector<Vec3>& positions, const EndBand& band, double orientation = 1.0);

//! The volume between two slices `h` apart whose section areas are a0 (neighbour) and a1 (end)
//! with slopes m0, m1 (mm²/mm, along the direction from the neighbour to the end): the integral of
//! the cubic Hermite area curve, h (a0 + a1) / 2 + h² (m0 − m1) / 12. Near a closing end (an apex
//! whose last section is small) the area falls fastest at the end, and this is larger than the
//! cone-like wall that fairing leaves between a large and a small contour.
double hermite_band_volume(double a0, double a1, double m0, double m1, double h);

//! Widens the wall's free vertices about the axis between the two centroids, by the factor
//! 1 + α φ(t), φ(t) = 16 t² (1 − t)² (0 with zero slope at the neighbouring slice and at the end contour,
//! so the wall keeps its slope across both; largest half-way), t the height from the neighbouring plane to
//! the end plane; α ∈ [0, 0.5] by bisection so that the wall encloses `target` (never narrowed; at most
//! 1.5× wider).
//! Returns α.
double fill_end_band(std::vector<Vec3>& positions, const EndBand& band, double target, double orientation = 1.0);

}  // namespace c4d
