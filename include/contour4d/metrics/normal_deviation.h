#pragma once
//! \file normal_deviation.h
//! \brief How far a surface's facets turn from a reference surface of the same shape: per triangle, the
//! angle between its normal and the normal of the reference triangle nearest its centroid. Distances
//! miss what shading shows: 0.05 mm of uneven error on 1 mm edges tilts facets by degrees (ridges and
//! cracks in a rendering), so decoded or carried meshes are also held to this.

#include <cstddef>

#include "contour4d/core/mesh.h"
#include "contour4d/metrics/surface_projector.h"

namespace c4d {

//! Facet normal angles against a reference (degrees); triangles of zero area are left out.
struct NormalDeviation {
  std::size_t triangles = 0;  //!< triangles measured
  double mean_deg = 0.0;      //!< mean angle
  double median_deg = 0.0;    //!< 50th percentile
  double p99_deg = 0.0;       //!< 99th percentile
  double max_deg = 0.0;       //!< largest angle
};

//! The angles between each triangle of `mesh` and the triangle of `reference` closest to its centroid.
//! Orientation counts: an inside-out facet is 180° off. \throw InvalidInput (BadMesh) when `reference` has
//! no triangle of non-zero area.
NormalDeviation normal_deviation(const TriangleMesh& mesh, const TriangleMesh& reference);

//! The same against a reference whose closest-point queries are already set up (its tree reused).
NormalDeviation normal_deviation(const TriangleMesh& mesh, const SurfaceProjector& reference);

}  // namespace c4d
