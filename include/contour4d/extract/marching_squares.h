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

//! `count` points evenly spaced by arc length along a closed polyline, starting at its first
//! vertex. count >= 3; a polyline of fewer than 2 points is returned unchanged.
std::vector<Vec2> resample_closed(const std::vector<Vec2>& polyline, int count);

//! Separable Gaussian blur of a width × height field (σ in pixels, kernel radius ceil(3σ); values
//! beyond the border count as 0). σ <= 0 returns the field unchanged.
std::vector<float> gaussian_blur(const std::vector<float>& field, int width, int height, double sigma);

}  // namespace c4d
