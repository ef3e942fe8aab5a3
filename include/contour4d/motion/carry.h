#pragma once
//! \file carry.h
//! \brief All frames, each on its own: frame 0's mesh carried onto every frame's own surface, every
//! frame independently of the others (Miara et al. §III.D–E: one base mesh, per-frame displacements;
//! Lim et al. 2014, "Contour Matching" for the contours that keep their partner).
//!
//! Per frame t: frame 0's contour chains are matched one-to-one to frame t's contours (same nesting parity)
//! and put on them by arc length (contour_matching.h); the rest of the mesh follows by a thin-plate
//! (biharmonic) displacement, one factorisation per set of matched chains, shared by the frames that have
//! it; where a dome retreated through a slice (an apex, a base or a myocardium's cavity whose contour
//! vanished), that dome of frame 0's mesh is scaled onto frame t's. Then rounds of tangential smoothing, the chain vertices
//! sliding along their contours and the others projected onto frame t's own surface sheet by sheet: a
//! vertex lands only on a part of the surface facing its own way, never on the nearest point of another
//! sheet (the inner and outer walls of a myocardium lie millimetres apart). Last, local untangling and
//! the small-angle repair (angle_repair.h), moves within the surface.
//! Frames do not wait for each other, so they run in parallel and the output does not depend on the
//! thread count.

#include <cstddef>
#include <functional>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! Options of carry_frames.
struct CarryOptions {
  double threshold = 0.3;   //!< similarity index for a chain↔contour match (Lim et al.: 30 %)
  int relax_rounds = 6;     //!< rounds of tangential smoothing, each followed by a projection
  double relax_step = 0.5;  //!< fraction of the way to the neighbours' centroid, in the tangent plane, per round
  double sheet_cos = 0.2;   //!< a vertex lands on the surface only where the landing triangle's normal and the
                            //!< vertex normal make an angle with at least this cosine (about 78°)
  int untangle_rounds = 4;  //!< rounds of local untangling where triangles cross after the relaxation (angle_repair.h)
  double angle_target_deg = 32.0;  //!< last, the vertices of triangles with an angle below this move within the surface
                                   //!< to raise their ring's smallest angle (angle_repair.h)
};

//! Per-frame figures of carry_frames.
struct CarryFrameReport {
  int source = -1;                 //!< the frame carried from (-1: not carried; carry_frames: 0)
  int matched_contours = 0;        //!< frame-0 chains matched one-to-one to this frame's contours
  int unmatched_chains = 0;        //!< chains without a partner (their contour split, merged or vanished)
  std::size_t fixed_vertices = 0;  //!< chain vertices put on this frame's contours
  std::size_t crossings = 0;       //!< crossing triangle pairs left by the untangling (0: none, or not tested)
  std::size_t angle_repairs = 0;   //!< vertex moves of the small-angle repair
  std::size_t off_sheet = 0;       //!< projections refused in the last round (landing on a sheet facing away)
  double projection_mean = 0.0;    //!< mean distance (mm) moved by the first projection
  double projection_max = 0.0;     //!< largest of the same
};

//! What carry_frames did.
struct CarryReport {
  std::vector<CarryFrameReport> frames;
  std::size_t factorisations = 0;  //!< distinct sets of matched chains (one sparse factorisation each)
};

//! Carries `frame0` (a closed mesh through frame 0's contours) onto every frame of `seq`.
//! `surface(t)` builds frame t's own surface; it is called once per frame t ≥ 1, from worker threads
//! (it must be thread-safe). Frame 0 keeps `frame0`'s positions.
//! \throw SolverError when a factorisation fails.
MeshSequence carry_frames(const Sequence& seq, const TriangleMesh& frame0,
                          const std::function<TriangleMesh(std::size_t)>& surface, const CarryOptions& options = {},
                          CarryReport* report = nullptr);

}  // namespace c4d
