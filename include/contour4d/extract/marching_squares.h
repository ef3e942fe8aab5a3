#pragma once
//! \file marching_squares.h
//! \brief Ordered closed iso-lines of a 2D scalar field (marching squares), and the smoothing and
//! resampling of closed polylines that turn a pixel staircase into a contour
//! (Miara et al. §III.B "Extraction des contours": an ordered chain of contour points).

#include <cstdint>
#include <vector>

#include "contour4d/core/vec.h"

namespace c4d {

//! Iso-lines of `field` (width × height values, x fastest: field[x + width·y]) at `level`, as
//! closed chains in pixel coordinates (x = column, y = row; pixel centres at integers). A pixel is
//! inside when its value is > level; each chain keeps the inside on its left, so with x right and y
//! up outer boundaries run counter-clockwise and holes clockwise. Crossings are placed by linear
//! interpolation along cell edges. Saddle cells join the two inside corners when the cell's mean
//! value is > level, else separate them (so on a 0/1 mask at level 0.5, diagonal neighbours are
//! separate components). Pixels outside the field count as 0 (below the level when level <= 0),
//! so every chain is closed.
//! Chains are ordered by their first crossing (row-major), deterministic, linear in pixels.
std::vector<std::vector<Vec2>> marching_squares(const std::vector<float>& field, int width, int height,
                                                float level = 0.5f);

//! Taubin λ|μ smoothing of a closed polyline (`passes` pairs of steps with the uniform umbrella
//! operator): shrinks the pixel staircase without shrinking the curve. λ > 0, μ < −λ.
void smooth_closed_taubin(std::vector<Vec2>& polyline, int passes, double lambda = 0.5, double mu = -0.53);

//! How fit_mask_staircase fits the contour of a point-sampled mask.
struct StaircaseFitOptions {
  int informative =
      4;  //!< each side of a vertex, the fit window holds at least this many vertices whose grid edge runs more along the curve than across it
  double max_window_px = 12.0;  //!< largest half-window (arc length, in pixels of the smaller spacing)
  double max_turn_deg =
      60.0;            //!< the window stops where the curve has turned this much (it stays a graph over the tangent)
  int iterations = 3;  //!< refits, each with the tangents of the previous one
  double tolerance =
      0.1;  //!< a fit crossing an edge (in the inner 60 % of its window) beyond a pixel centre by more than this fraction of the half edge is rejected: the window shrinks
  int degree =
      3;  //!< degree of the local polynomial over the tangent (1..3; 3 follows curvature that varies along the window)
};

//! Sub-pixel contour of a 0/1 mask from its marching-squares chain (level 0.5): each vertex of
//! `chain` is the midpoint of the grid edge between an inside and an outside pixel centre, so the
//! true boundary crosses that edge somewhere within ±½ edge of it, an uncertainty that lies along
//! the edge. Around each vertex a cubic over the local tangent is fitted to the vertices nearby,
//! each weighted by the inverse of its uncertainty across the curve ((½ edge)²/3 · (edge · normal)²):
//! near an axis-parallel stretch the run ends (edges along the curve) fix the curve and the run
//! midpoints (edges across it) hardly count. The window grows until it holds `informative` such
//! vertices on each side (so it spans a few pixel rows whatever the curvature; a polynomial over it
//! has no curvature bias, unlike Laplacian-type smoothing), and shrinks while the fit crosses an
//! edge outside its two pixel centres (the mask's own constraint; the wrong model there). The new
//! vertex is where the accepted fit crosses the vertex's own edge, clamped between its pixel
//! centres; with no consistent fit, the edge midpoint. Three rounds, each with the previous
//! round's tangents (the first from a Taubin-smoothed chain). docs/images.md gives the figures.
//! \param chain  one closed chain of marching_squares on a 0/1 field (pixel coordinates)
//! \param spacing  pixel size along x and y (mm); the result is in mm (pixel coordinate × spacing)
//! \return one point per vertex, same order. Chains of fewer than 5 vertices are only scaled.
std::vector<Vec2> fit_mask_staircase(const std::vector<Vec2>& chain, Vec2 spacing,
                                     const StaircaseFitOptions& options = {});

//! `count` points evenly spaced by arc length along a closed polyline, starting at its first
//! vertex. count >= 3; a polyline of fewer than 2 points is returned unchanged.
std::vector<Vec2> resample_closed(const std::vector<Vec2>& polyline, int count);

//! Separable Gaussian blur of a width × height field (σ in pixels, kernel radius ceil(3σ); values
//! beyond the border count as 0). σ <= 0 returns the field unchanged.
std::vector<float> gaussian_blur(const std::vector<float>& field, int width, int height, double sigma);

}  // namespace c4d
