#pragma once
//! \file quality.h
//! \brief Triangle angle quality (Lim et al. 2014, Tables 3 and 4): the share of angles between 40
//! and 80 degrees, in 10-degree bins, and the triangles with an angle below 25 degrees.

#include <cstddef>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of angle_quality.
struct AngleQualityOptions {
  double bad_angle_deg = 25.0;  //!< a triangle with a smaller angle is "bad quality" (Table 4)
};

//! Angle statistics of one mesh. Bins are half-open [40,50), [50,60), [60,70), [70,80); the
//! percentages count angles (three per triangle), as in Table 3.
struct AngleQuality {
  std::size_t triangles = 0;      //!< triangles measured
  double pct_40_50 = 0.0;         //!< % of angles in [40°, 50°)
  double pct_50_60 = 0.0;         //!< % of angles in [50°, 60°)
  double pct_60_70 = 0.0;         //!< % of angles in [60°, 70°)
  double pct_70_80 = 0.0;         //!< % of angles in [70°, 80°)
  double pct_40_80 = 0.0;         //!< % of angles in [40°, 80°): the sum of the four bins
  std::size_t bad_triangles = 0;  //!< triangles with an angle below bad_angle_deg (zero-area ones included)
  double bad_pct = 0.0;           //!< bad_triangles as % of all triangles
  double min_angle_deg = 0.0;     //!< smallest angle of the mesh (degrees); 0 for a zero-area triangle
  double max_angle_deg = 0.0;     //!< largest angle of the mesh (degrees)
};

//! Angles from atan2(|a×b|, a·b), accurate for needle triangles too. Triangles with an index out
//! of range are skipped.
AngleQuality angle_quality(const TriangleMesh& mesh, const AngleQualityOptions& options = {});

//! How many of triangle (a, b, c)'s angles lie in [40°, 80°), measured as angle_quality measures them
//! (0 for a zero-area triangle).
int angles_40_80(Vec3 a, Vec3 b, Vec3 c);

}  // namespace c4d
