#pragma once
// The tuning constants of the one-frame surface's steps (reconstruct.cpp), in one struct so that a white-box
// test can switch a step off (tests/unit/reconstruct_internal_test.cpp); the library always uses the defaults.

#include "contour4d/surface/angle_repair.h"
#include "contour4d/surface/reconstruct.h"

namespace c4d::detail {

struct SurfaceTuning {
  double corner_angle_deg = 30;     // contour vertices turning more than this are kept exactly
  double min_contour_gap = 0.02;    // contours of one slice closer than this (mm; touching at a saddle) move apart
  double contour_tolerance = 0.01;  // resampled contours stay about this close to the input (mm): finer on bends
  double cap_height = 0.5;          // Rounded cap height as a fraction of the adjacent slice spacing (≤ 0.5)
  double cap_max_fill = 0.95;       // a faired Rounded cap is lifted (never lowered) towards the volume the trend
                                    // of the last two section areas gives, at most this fraction of the prism
                                    // (capping.h, extrapolated_cap_volume)
  double row_spacing = 0.0;         // rows' spacing across a band (mm, on its slant width); 0: the edge length
  bool remesh = true;               // isotropic remeshing of the bands without rows (branchings; all with rows = false)
  int remesh_iterations = 5;        // its rounds with CGAL's remesher
  int fast_remesh_iterations = 10;  // its rounds with ours (cheaper rounds)
  RemeshEngine rows_remesher = RemeshEngine::Fast;  // the remesher with rows (branchings and the final remeshing)
  int final_remesh_iterations = 3;  // rounds of remeshing of the whole faired surface, contours kept (rows = false)
  int rows_final_remesh_iterations = 3;  // the same with rows: evens out rows sheared where a band twists
  AngleRepairOptions angle_repair{.target_deg = 28.0};  // last: the small-angle repair (target from SurfaceOptions)
  bool fairing = true;                                  // thin-plate fairing with the contours fixed (fairing.h)
};

// The options a step reads: the caller's and the tuning, under one name.
struct SurfaceParams : SurfaceOptions, SurfaceTuning {};

// The caller's options with the default tuning; geometry_only surfaces skip what only the output needs.
SurfaceParams surface_params(const SurfaceOptions& options, const SurfaceTuning& tuning = {});

// reconstruct_frame (reconstruct.h) with the tuning given.
TriangleMesh reconstruct_frame_tuned(const Sequence& seq, int frame, const SurfaceParams& params,
                                     SurfaceReport* report = nullptr);

}  // namespace c4d::detail
