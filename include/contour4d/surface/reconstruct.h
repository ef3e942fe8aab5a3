#pragma once
//! \file reconstruct.h
//! \brief The surface of one frame from its contours (Lim et al. 2014, "Constructing a 3D model of
//! the First Cardiac Frame"): canonical resampled contours → tree-based connectivity → tiling
//! between connected contours (rows; branching bridges) → caps → thin-plate fairing with the contours fixed.

#include <string>
#include <vector>

#include "contour4d/connect/connectivity.h"
#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/surface/angle_repair.h"
#include "contour4d/surface/capping.h"
#include "contour4d/surface/refine.h"

namespace c4d {

//! How the surface between two connected slices is triangulated.
enum class Tiling {
  Bands,     //!< optimal bands between the contours (Fuchs et al. 1977; bridges for branching), then remeshed
  Delaunay,  //!< the paper's: constrained Delaunay of the projected symmetric difference, CAT lifting points
             //!< (Barequet & Sharir 1996; delaunay_tiling.h), then remeshed
};

//! Options of the one-frame surface.
struct SurfaceOptions {
  std::string label;             //!< structure to build; empty: the frame must hold a single label
  double edge = 1.0;             //!< target edge length (mm): contour resampling, rows, caps and remeshing
  double corner_angle_deg = 30;  //!< contour vertices turning more than this are kept exactly
  double min_contour_gap = 0.02;  //!< contours of one slice closer than this (mm; e.g. touching at a saddle) are moved apart to it
  double contour_tolerance = 0.01;  //!< resampled contours stay about this close to the input (mm): finer spacing on bends (0: spacing `edge`)
  CapStyle caps = CapStyle::Rounded;  //!< how ends are closed
  double cap_height = 0.5;       //!< Rounded cap height as a fraction of the adjacent slice spacing (≤ 0.5)
  double cap_max_fill = 0.95;    //!< after fairing, a Rounded cap is lifted (never lowered) to the volume the
                                 //!< linear trend of the last two section areas gives past the end contour, at
                                 //!< most this fraction of the prism area × cap height (capping.h,
                                 //!< extrapolated_cap_volume); 0: faired domes as they are
  double threshold = 0.3;        //!< similarity threshold of the connectivity tree (paper: 30 %)
  Tiling tiling = Tiling::Bands;  //!< triangulation between slices (Delaunay falls back to Bands, with a warning,
                                  //!< on a slice pair it cannot tile). With rows, 1→1 bands get rows either way:
                                  //!< Delaunay on every band needs rows = false (the CLI's --tiling delaunay sets it)
  bool rows = true;              //!< true: 1→1 bands get interpolated rows (row_spacing apart) instead of being
                                 //!< remeshed; the faired surface is evened out by rows_final_remesh_iterations rounds
                                 //!< of remeshing (1.9–3.2× faster per frame than false, the remeshed bands path)
  double row_spacing = 0.0;      //!< rows: the rows' spacing across a band (mm), measured on the band's slant width
                                 //!< (interpolate_rows); 0: edge. Rows one edge apart fair closer to the true surface
                                 //!< than equilateral ones (edge·√3/2): left heart ES slab mean 0.0167 against 0.0211 mm
  bool remesh = true;            //!< isotropic remeshing (CGAL) of the bands without rows (branchings; all bands when rows = false)
  int remesh_iterations = 5;     //!< remeshing rounds of each band before fairing (remesher = Cgal)
  int fast_remesh_iterations = 10;  //!< the same with remesher = Fast (cheap rounds; left-heart ED slab max
                                    //!< 0.55 mm after 5, 0.37 mm after 10)
  RemeshEngine remesher = RemeshEngine::Cgal;  //!< implementation of both remeshings (refine.h) with rows = false:
                                               //!< Cgal (default) or Fast (isotropic_remesh.h: about 2× faster per
                                               //!< frame; the surface differs, slab accuracy within about ±10 % of
                                               //!< Cgal's, smallest angles not guaranteed)
  RemeshEngine rows_remesher = RemeshEngine::Fast;  //!< the same with rows = true (branchings and the final remeshing):
                                                    //!< Fast by default, 1.3–1.6× faster per frame than Cgal with
                                                    //!< the same or better shapes and accuracy on every phantom and
                                                    //!< on the real data (one_frame_surface.md)
  int final_remesh_iterations = 3;  //!< isotropic remeshing rounds of the whole faired surface, contours kept as
                                    //!< fixed chains of edges (evens out triangles that fairing stretched at
                                    //!< branchings and caps); 0: none. rows = true uses rows_final_remesh_iterations
  int rows_final_remesh_iterations = 3;  //!< the same with rows = true: the faired rows sheared where a band twists
                                         //!< (coarse, irregular real contours: 61–69 % of angles in 40–80° without it,
                                         //!< 96–97 % with it); 0: none (the 4D run's later-frame targets)
  AngleRepairOptions angle_repair{.target_deg = 28.0};  //!< last: vertices of triangles with an angle below
                                    //!< angle_repair.target_deg move within the surface to maximise their ring's smallest
                                    //!< angle (passes = 0: off). 28°, 3° above the 25° the quality targets count: at 32°
                                    //!< (the morph's target) the left heart ES frame takes 1.25× as long, with no fewer
                                    //!< triangles below 25° and 0.5 point fewer angles in 40–80°. The 4D run's frame 0
                                    //!< uses the morph's target (reconstruct4d.h)
  bool fairing = true;           //!< thin-plate fairing with the contours fixed: smooth across contours (fairing.h)
  double cap_shape_weight = 0.0; //!< fairing weight keeping the initial Rounded dome shape (0: the dome is faired freely and continues the wall; its tip is still clamped to cap_height)
  int smoothing_iterations = 0;  //!< λ|μ|ε pass pairs after fairing (0: none); contour vertices fixed
  double smoothing_epsilon = 0.2;  //!< ε bound of the smoothing (mm)
  bool check_self_intersections = true;  //!< run CGAL's self-intersection test for the report
};

//! What reconstruct_frame did, for logs and the CLI summary.
struct SurfaceReport {
  std::vector<Connection> connections;  //!< above/below links used (slice ids, input contour indices)
  int contours = 0;            //!< contours of the frame used
  int caps = 0;                //!< caps made (CapStyle::Open: ends left open)
  int branchings = 0;          //!< slice pairs joined through bridges (1→n, n→1, n→m)
  std::size_t vertices = 0;    //!< output vertex count
  std::size_t triangles = 0;   //!< output triangle count
  bool closed = false;         //!< closed 2-manifold, consistently oriented
  bool self_intersects = false;  //!< CGAL found intersecting triangles (when checked)
  bool self_intersections_checked = false;  //!< the self-intersection test ran (SurfaceOptions::check_self_intersections)
  long euler = 0;              //!< Euler characteristic V - E + F
  int components = 0;          //!< connected components
  double volume = 0.0;         //!< signed volume (mm³), > 0 when outward
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

}  // namespace c4d
