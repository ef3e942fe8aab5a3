#pragma once
//! \file contour_fit.h
//! \brief A final, small fit of a morphed frame's mesh onto that frame's contours (Lim et al. 2014,
//! "Mesh Conformity": the surface must pass through every input contour; their conformity is
//! measured every 0.2 mm along the contours). Where the held chains of a band let the relaxation
//! carry vertices through a slice plane, the mesh section cuts across the contour between vertices
//! by up to about a millimetre; this fit moves the vertices near such places by a smooth,
//! least-squares displacement so that the surface passes through the contour samples.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of fit_to_contours (defaults: what the 4D morph uses).
struct ContourFitOptions {
  double step_mm = 0.2;        //!< contour samples this far apart along each contour (as `evaluate`'s conformity)
  double tolerance_mm = 0.05;  //!< samples nearer the mesh than this start no correction (they still hold their
                               //!< part of the mesh in place where a correction reaches it)
  double reach_mm = 1.5;       //!< samples farther from the mesh than this are left alone (no sheet to move there)
  int iterations = 3;          //!< closest-point and solve rounds (0: only measure, max_before_mm)
  int rings = 2;               //!< the vertices that move: those of the triangles nearest the far samples and
                               //!< this many rings of neighbours around them (the rest stay)
  double smoothness = 1.0;     //!< weight of the displacement's uniform Laplacian against the sample residuals
  double damping = 0.05;       //!< weight of the displacement itself (keeps the system regular)
};

//! What fit_to_contours did.
struct ContourFitReport {
  double max_before_mm = 0;  //!< largest sample distance to the mesh before the fit (within reach_mm)
  double max_after_mm = 0;   //!< the same after it
  std::size_t moved = 0;     //!< vertices moved
};

//! Moves vertices of (x, triangles) so that the surface passes through samples of `contours` (closed
//! polylines, mm): Gauss–Newton rounds of closest points, then the displacement of the vertices near
//! far samples that best puts each sample's closest point onto it with a smooth (Laplacian-penalised)
//! field. Vertices flagged in `fixed` do not move. Deterministic; thread-count independent.
ContourFitReport fit_to_contours(std::vector<Vec3>& x, const std::vector<Triangle>& triangles,
                                 const std::vector<std::vector<Vec3>>& contours, const std::vector<char>& fixed,
                                 const ContourFitOptions& options = {});

//! The same with the samples given: points the surface should pass through (mm).
//! `sample_triangles` (optional, in and out): per sample, the triangle (index in `triangles`; −1: none)
//! its closest point was found on, by an earlier call on the same samples and triangles at nearby positions.
//! The first closest-point round then walks over the surface from there (without them, each sample walks
//! from the answer of the sample before it); on return it holds this call's last answers.
ContourFitReport fit_to_points(std::vector<Vec3>& x, const std::vector<Triangle>& triangles,
                               const std::vector<Vec3>& samples, const std::vector<char>& fixed,
                               const ContourFitOptions& options = {},
                               std::vector<std::int32_t>* sample_triangles = nullptr);

//! The samples fit_to_contours uses: points every `step` mm along each closed polyline.
std::vector<Vec3> contour_fit_samples(const std::vector<std::vector<Vec3>>& contours, double step);

}  // namespace c4d
