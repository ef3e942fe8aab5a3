#pragma once
//! \file tet_quality.h
//! \brief Shape and validity of tetrahedra: signed volume, smallest dihedral angle, aspect ratio.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "contour4d/core/tet_mesh.h"

namespace c4d {

//! The figures of one set of node positions over all tets.
struct TetQuality {
  double volume_mm3 = 0.0;           //!< sum of the signed volumes (the cavity's volume)
  double min_volume_mm3 = 0.0;       //!< the smallest signed volume
  std::size_t inverted = 0;          //!< tets with signed volume <= 0
  std::size_t first_inverted = 0;    //!< the lowest index of an inverted tet (when inverted > 0)
  double min_dihedral_deg = 180.0;   //!< the smallest dihedral angle of a valid tet (degrees)
  double max_aspect_ratio = 0.0;     //!< the largest aspect ratio of a valid tet
  std::size_t worst_aspect_tet = 0;  //!< where it is
};

//! Aspect ratio of a tet, Verdict's (C. J. Stimpson et al., "The Verdict geometric quality library", SAND2007-1751):
//! longest edge / (2√6 · inradius), 1 for the regular tet, growing without bound as it flattens; infinite when
//! the volume is <= 0.
double tet_aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

//! Smallest of the six dihedral angles of a tet (degrees).
double tet_min_dihedral_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

//! Measures every tet of `tets` at node positions `nodes` (mm).
TetQuality measure_tets(const std::vector<Vec3>& nodes, const std::vector<Tet>& tets);

}  // namespace c4d
