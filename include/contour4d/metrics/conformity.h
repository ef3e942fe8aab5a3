#pragma once
//! \file conformity.h
//! \brief Mesh conformity (Lim et al. 2014, "Mesh Conformity"): distance from points taken every
//! 0.2 mm along the input contours to the nearest point of the frame's mesh.

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/metrics/distance.h"

namespace c4d {

//! Options of contour_conformity.
struct ConformityOptions {
  double step = 0.2;  //!< sampling interval along each closed contour (mm); the paper's value
};

//! Distances (mm) from arc-length samples of every contour of `frame` to the surface of `mesh`
//! (exact point-to-triangle distance, AABB tree). Unweighted statistics over all samples.
//! \throw InvalidInput when the mesh has no triangle of non-zero area.
DistanceStats contour_conformity(const TriangleMesh& mesh, const Frame& frame, const ConformityOptions& options = {});

}  // namespace c4d
