#pragma once
//! \file section.h
//! \brief The section of a closed triangle mesh by a plane: closed loops of points on the mesh.

#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/plane.h"

namespace c4d {

//! Loops where `mesh` meets `plane`, each an ordered closed polygon of points on mesh edges (mm).
//! Vertices exactly on the plane count as lying above it (symbolic perturbation), so every loop is
//! closed for a closed manifold mesh; consecutive duplicate points are removed. Loops are ordered
//! by their first edge, so the result is deterministic.
std::vector<std::vector<Vec3>> plane_section(const TriangleMesh& mesh, const Plane& plane);

}  // namespace c4d
