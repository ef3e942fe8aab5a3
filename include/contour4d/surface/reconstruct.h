#pragma once
//! \file reconstruct.h
//! \brief The surface of one frame from its contours (Lim et al. 2014, "Constructing a 3D model of
//! the First Cardiac Frame"): canonical resampled contours → tree-based connectivity → tiling
//! between connected contours (rows; branching bridges) → caps → thin-plate fairing with the contours fixed.

#include <optional>
#include <string>
#include <vector>

#include "contour4d/connect/connectivity.h"
#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/surface/angle_repair.h"
#include "contour4d/surface/capping.h"
#include "contour4d/surface/refine.h"
#include "contour4d/surface/surface_plan.h"

namespace c4d {

//! How the surface between two connected slices is triangulated.
enum class Tiling {
  Bands,     //!< optimal bands between the contours (Fuchs et al. 1977; bridges for branching), then remeshed
  Delaunay,  //!< the paper's: constrained Delaunay of the projected symmetric difference, CAT lifting points
             //!< (Barequet & Sharir 1996; delaunay_tiling.h), then remeshed
};

//! Options of the one-frame surface: what a user or a calling stage sets. The tuning constants of each step
//! (contour resampling tolerance, cap height, remeshing rounds, fairing) live beside the code that uses them
//! (src/surface/surface_tuning_internal.h).
struct SurfaceOptions {
  std::string label;                  //!< structure to build; empty: the frame must hold a single label
  double edge = 1.0;                  //!< target edge length (mm): contour resampling, rows, caps and remeshing
  CapStyle caps = CapStyle::Rounded;  //!< how ends are closed
  double threshold = 0.3;             //!< similarity threshold of the connectivity tree (paper: 30 %)
  Tiling tiling = Tiling::Bands;      //!< triangulation between slices (Delaunay falls back to Bands, with a
                                      //!< warning, on a slice pair it cannot tile; it needs rows = false)
  bool rows = true;                   //!< 1→1 bands get interpolated rows (fast); false: every band is remeshed
                                      //!< isotropically (even triangles: the 4D run's frame 0, the Delaunay tiling)
  RemeshEngine remesher = RemeshEngine::Cgal;  //!< the isotropic remeshing of the bands when rows = false: CGAL's
                                               //!< or ours (Fast, isotropic_remesh.h; the 4D run's frame 0)
  double angle_target_deg = 28.0;        //!< last, the small-angle repair moves vertices of triangles with an angle
                                         //!< below this within the surface (angle_repair.h); the 4D run's frame 0 uses
                                         //!< the all-frames stage's target (32°)
  bool geometry_only = false;            //!< the surface only serves as a target to project onto (the 4D run's later
                                         //!< frames): rows, no final remeshing, no small-angle repair, no
                                         //!< self-intersection test
  bool check_self_intersections = true;  //!< run CGAL's self-intersection test for the report
};

//! What reconstruct_frame did, for logs and the CLI summary.
struct SurfaceReport {
  std::vector<Connection> connections;  //!< above/below links used (slice ids, input contour indices)
  int contours = 0;                     //!< contours of the frame used
  int caps = 0;                         //!< caps made (CapStyle::Open: ends left open)
  int branchings = 0;                   //!< slice pairs joined through bridges (1→n, n→1, n→m)
  int opening_holes = 0;                //!< holes joined to their ring's partner where the ring opens between slices
  std::size_t vertices = 0;             //!< output vertex count
  std::size_t triangles = 0;            //!< output triangle count
  bool closed = false;                  //!< closed 2-manifold, consistently oriented
  bool self_intersects = false;         //!< CGAL found intersecting triangles (when checked)
  bool self_intersections_checked =
      false;                          //!< the self-intersection test ran (SurfaceOptions::check_self_intersections)
  long euler = 0;                     //!< Euler characteristic V - E + F
  int components = 0;                 //!< connected components
  double volume = 0.0;                //!< signed volume (mm³), > 0 when outward
  std::vector<std::string> warnings;  //!< problems that did not stop the reconstruction
};

//! Builds the surface of frame `frame` of `seq`: a closed (unless CapStyle::Open), 2-manifold,
//! outward-oriented triangle mesh in world coordinates (mm) on which every (resampled) input
//! contour is a closed chain of mesh edges. Result is independent of contour start points,
//! orientation, slice order and (up to rounding) rigid motion of the input.
//! \throw InvalidInput when the frame does not exist, holds no contour of the label, or holds
//! several labels and none was chosen.
TriangleMesh reconstruct_frame(const Sequence& seq, int frame, const SurfaceOptions& options = {},
                               SurfaceReport* report = nullptr);

//! The plan of frame `frame`'s surface (surface_plan.h): its counts and triangles with `options`, the final
//! remeshing and edge flips left out (they would tie the triangles to this frame's geometry). The plan is
//! unusable (SurfacePlan::unusable says why) where contours branch between slices, with the Delaunay tiling
//! or without rows.
//! \throw InvalidInput as reconstruct_frame.
SurfacePlan plan_surface(const Sequence& seq, int frame, const SurfaceOptions& options = {});

//! Frame `frame`'s own surface built on `plan`: the plan's vertices and triangles, this frame's geometry
//! (contours sampled at the plan's counts from matched starts, rows along the plan's spanning edges, caps by
//! mean-value coordinates, then fairing, filling and the small-angle repair, which only move vertices).
//! std::nullopt when the frame's contours do not fit the plan (other slices, contour counts, nesting or
//! links; `why_not` says which) or the plan is unusable.
//! \throw InvalidInput as reconstruct_frame.
std::optional<TriangleMesh> reconstruct_frame_on_plan(const Sequence& seq, int frame, const SurfaceOptions& options,
                                                      const SurfacePlan& plan, SurfaceReport* report = nullptr,
                                                      std::string* why_not = nullptr);

}  // namespace c4d
