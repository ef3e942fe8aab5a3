#pragma once
//! \file cavity_mesh.h
//! \brief The tetrahedral mesh of a closed surface's cavity (TetGen), its surface triangles kept as its
//! boundary faces, unchanged.

#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/tet_mesh.h"

namespace c4d {

//! What TetGen is asked for (docs/export.md, "Volume mesh").
struct CavityMeshOptions {
  double radius_edge = 1.5;      //!< bound on a tet's circumradius / shortest edge (TetGen -q)
  double min_dihedral_deg = 12;  //!< bound on a tet's smallest dihedral angle (TetGen -q …/angle)
  double max_volume_mm3 = 0.0;   //!< largest tet (TetGen -a); 0: none (tets grow away from the wall)
};

//! Fills the closed, outward, self-intersection-free `surface` with tetrahedra: TetGen 1.5 (H. Si, "TetGen, a
//! Delaunay-based quality tetrahedral mesh generator", ACM TOMS 41(2), 2015) with -p (a piecewise linear complex:
//! every triangle its own facet), -Y and -M (no Steiner point on the boundary, no merged facets: the surface
//! triangles are the boundary faces, unchanged) and -q (quality, by points inside only). Nodes
//! [0, surface vertices) are the surface's vertices in order; every tet is positively oriented.
//! \throw SolverError (VolumeMeshFailed) with TetGen's reason (self-intersection, tiny features, ...) or when a
//! surface triangle is not a face of the result.
TetMesh mesh_cavity(const TriangleMesh& surface, const CavityMeshOptions& options = {});

}  // namespace c4d
