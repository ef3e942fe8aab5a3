#pragma once
//! \file smoothing.h
//! \brief λ|μ|ε smoothing (Lim et al. 2014, "Surface Smoothing and Refinement", eq. 7): Taubin's
//! volume-preserving λ|μ smoothing with each step bounded by ε along the vertex normal.

#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of λ|μ|ε smoothing.
struct SmoothingOptions {
  int iterations = 10;      //!< λ and μ pass pairs
  double lambda = 0.5;      //!< shrinking step, 0 < λ < 1
  double pass_band = 0.05;  //!< k_PB = 1/λ + 1/μ (paper: 0.01–0.1); μ is derived from it
  double epsilon = 0.2;     //!< largest move along the normal per pass (mm); <= 0 disables the bound
};

//! Smooths `mesh` in place with umbrella weights; vertices with fixed[v] != 0 do not move (the
//! input contours). When a pass moves a vertex more than ε along its normal (Max 1999 weights),
//! the move is scaled back so that the normal part is ε.
//! \pre fixed is empty or has one entry per vertex.
void smooth_lambda_mu_epsilon(TriangleMesh& mesh, const std::vector<char>& fixed, const SmoothingOptions& options = {});

//! Per-vertex unit normals (Max 1999: face normals weighted by sin(angle)/(|e1||e2|)).
std::vector<Vec3> vertex_normals(const TriangleMesh& mesh);

}  // namespace c4d
