#pragma once
//! \file fairing.h
//! \brief Thin-plate fairing with fixed contours (replaces and improves on Lim et al. 2014,
//! "Surface Smoothing and Refinement", eq. 7): one sparse solve makes the surface smooth across
//! every contour while it still passes through the contours exactly.

#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of fairing.
struct FairingOptions {
  double shape_weight =
      1.0;  //!< weight of the shape-keeping terms (vertices with keep_shape set) against the smoothness terms
  std::vector<double> row_scale;  //!< per vertex, a factor on its term's row (its weight: the factor squared); empty:
                                  //!< 1 everywhere. The umbrella Laplacian grows with the edge length squared, so
                                  //!< a region meshed s times coarser weighs s² as much per area: 1/s there keeps
                                  //!< the balance (reconstruct_frame's caps without walls)
  std::vector<char> scale_aware;  //!< per vertex (empty: none): its term weighs each neighbour u by
                                  //!< reference_edge / |x_u − x_v| (measured before fairing) besides the
                                  //!< uniform 1/n: the scale-dependent umbrella (Desbrun et al. 1999) scaled
                                  //!< to the uniform one's size on a mesh of `reference_edge`. Where a region
                                  //!< meshed coarser meets a finer one (reconstruct_frame's ring caps),
                                  //!< the uniform umbrella matches the two sides' steps, not their slopes,
                                  //!< and flattens the coarse side; this one matches the slopes
  double reference_edge = 1.0;    //!< the edge length (mm) at which a scale-aware term equals the uniform one
};

//! Moves the free vertices (fixed[v] == 0) of `mesh` to minimise Σ_v w_v |L(x)_v − b_v|², L the
//! uniform (umbrella) Laplacian: b_v = 0 (smooth, ≈ C1 across fixed vertices, since the terms of the
//! fixed vertices couple both sides) except where keep_shape[v] != 0, where b_v is the Laplacian of
//! the input positions (the shape there is kept up to a smooth correction; used for rounded caps).
//! Vertices flagged in options.scale_aware use the scale-dependent umbrella instead (FairingOptions).
//! Terms of boundary vertices (open ends) are left out. Fixed vertices do not move at all.
//! One sparse LDLᵀ factorisation (Eigen), three right-hand sides. Returns false (mesh unchanged)
//! when the system cannot be factorised, e.g. a component without fixed vertex.
//! \pre fixed, keep_shape and options.row_scale are empty or have one entry per vertex.
bool fair_thin_plate(TriangleMesh& mesh, const std::vector<char>& fixed, const std::vector<char>& keep_shape,
                     const FairingOptions& options = {});

}  // namespace c4d
