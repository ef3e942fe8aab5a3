#pragma once
//! \file distance.h
//! \brief Surface-to-surface distance between a mesh and a ground-truth mesh, both ways, with the
//! symmetric Hausdorff distance (Lim et al. 2014, Table 5: mean, max and RMS in mm).

#include <cstddef>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/vec.h"

namespace c4d {

//! Summary of a set of distances (mm). For surface samples mean, rms and std are area-weighted.
struct DistanceStats {
  std::size_t samples = 0;  //!< number of points measured
  double mean = 0.0;        //!< mean distance (mm)
  double max = 0.0;         //!< largest distance (mm)
  double rms = 0.0;         //!< root mean square distance (mm)
  double std = 0.0;         //!< standard deviation of the distance (mm)
};

//! Unweighted summary of `distances` (all zero when empty).
DistanceStats summarize_distances(const std::vector<double>& distances);

//! A surface sample point with the area it stands for (0 for vertices: they only count in max).
struct SurfaceSample {
  Vec3 point;         //!< position (mm)
  double area = 0.0;  //!< quadrature weight (mm²)
};

//! How sample points are placed on a surface: deterministic, no random numbers.
struct SurfaceSamplingOptions {
  double spacing =
      0.5;  //!< target sample spacing (mm): a triangle whose longest edge is L is split into n² similar sub-triangles, n = ceil(L / spacing)
  int max_subdivision = 16;  //!< cap on n per triangle (at most 256 samples per triangle)
};

//! Every vertex (weight 0) plus the centroid of each sub-triangle of a regular barycentric
//! subdivision of every triangle (weight: the sub-triangle's area), in triangle order.
std::vector<SurfaceSample> sample_surface(const TriangleMesh& mesh, const SurfaceSamplingOptions& options = {});

//! A slab between two planes perpendicular to `normal`: points p with
//! min_offset <= dot(p, normal) <= max_offset.
struct Slab {
  Vec3 normal{0, 0, 1};     //!< unit stack normal
  double min_offset = 0.0;  //!< offset of the first slice plane (mm)
  double max_offset = 0.0;  //!< offset of the last slice plane (mm)
};

//! Distances both ways between two surfaces.
struct SurfaceDistance {
  DistanceStats mesh_to_truth;  //!< from samples of the mesh to the truth surface
  DistanceStats truth_to_mesh;  //!< from samples of the truth to the mesh surface
  double hausdorff = 0.0;       //!< symmetric Hausdorff distance: the larger of the two maxima (mm)
};

//! Options of compare_surfaces.
struct SurfaceDistanceOptions {
  SurfaceSamplingOptions sampling;  //!< sample placement on both surfaces
  bool use_slab = false;            //!< also measure on samples inside `slab` only
  Slab slab;                        //!< the slab between the first and last slice (when use_slab)
};

//! Whole-surface distances and, when asked, the same restricted to the slab.
struct SurfaceComparison {
  SurfaceDistance whole;  //!< every sample
  bool has_slab = false;  //!< true when `slab` was measured
  SurfaceDistance slab;   //!< only samples whose offset along the slab normal lies inside the slab
};

//! Exact point-to-triangle distances (AABB tree) from the samples of each surface to the other.
//! \throw InvalidInput when either mesh has no triangle of non-zero area.
SurfaceComparison compare_surfaces(const TriangleMesh& mesh, const TriangleMesh& truth,
                                   const SurfaceDistanceOptions& options = {});

}  // namespace c4d
