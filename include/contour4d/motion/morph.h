#pragma once
//! \file morph.h
//! \brief 4D morphing: the frame-0 mesh carried through every frame with the same vertices and
//! triangles (Lim et al., "4D Morphing of the Heart Model"; Miara et al. §III.E).

#include <functional>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/motion/vertical_deformation.h"
#include "contour4d/surface/angle_repair.h"

namespace c4d {

//! How a frame's mesh is obtained from the previous one.
enum class MorphMethod {
  Rbf,         //!< the paper: match mesh sections to the next contours, Hardy-multiquadric RBF in sub-steps
  RbfProject,  //!< default: the paper's RBF as a first guess, then a Laplacian-regularised projection onto the
               //!< frame's own reconstructed surface and tangential relaxation (exact fit, kept quality)
};

//! Options of the morphing stage: what a user or caller sets. The steps' tuning lives beside their code
//! (src/motion/morph*.cpp; docs/algorithms/morph.md gives the figures behind each value).
struct MorphOptions {
  MorphMethod method = MorphMethod::RbfProject;  //!< see MorphMethod
  int rbf_steps = 10;                 //!< RBF sub-steps against crossing paths (paper: 10); RbfProject uses 1
  int sources_per_contour = 48;       //!< chain points per matched contour used as RBF sources (Rbf; RbfProject's
                                      //!< first guess takes 24: the projection and relaxation refine the rest)
  double threshold = 0.3;             //!< similarity for a chain↔contour match (paper: 30 %)
  bool vertical_deformation = false;  //!< Lim et al.'s sine vertical pre-deformation (eq. 10, Table 1) at slices whose
                                      //!< contours split or merge, before the matching (vertical_deformation.h)
  VerticalDeformationOptions vertical;  //!< its options
  //! RbfProject, after the relaxation: vertices of triangles with an angle below angle_repair.target_deg move
  //! within the surface to maximise their ring's smallest angle (passes = 0: off; twice the surface's passes,
  //! as saddles need them). reconstruct_4d gives frame 0's surface the same target.
  AngleRepairOptions angle_repair{.passes = 8};
};

//! A 2D contour topology change on one slice between two frames.
struct SliceEvent {
  int frame = 0;     //!< the later frame
  int slice = 0;     //!< slice id
  std::string kind;  //!< "split", "merge", "appear", "vanish" or "change"
  int before = 0;    //!< contours (mesh section loops) on the slice in the earlier frame
  int after = 0;     //!< contours on the slice in the later frame
};

//! Miara et al. Fig. 14: a sub-mesh between two adjacent slices serves over a run of frames; a
//! change in the contours on either slice starts another.
struct SubMeshLifetime {
  int slice_below = 0, slice_above = 0;  //!< slice ids (by offset)
  int first_frame = 0, last_frame = 0;   //!< inclusive
  int contours_below = 0, contours_above = 0;
};

//! Per-frame figures of the morph.
struct MorphFrameReport {
  int matched = 0;                     //!< section↔contour matches used as RBF constraints
  int sources = 0;                     //!< RBF source points
  std::size_t intersecting_pairs = 0;  //!< triangle pairs still intersecting after untangling (RbfProject)
  std::size_t angle_repairs = 0;       //!< vertex moves of the small-angle repair
  std::size_t sliding = 0;             //!< contour-chain vertices kept on their contour (RbfProject)
  int plane_snapped = 0;               //!< vertices put on a contour where an edge crosses its plane (RbfProject)
  std::size_t fit_moved = 0;   //!< vertices moved by the last contour fit (RbfProject; 0: none, or no harmless fit)
  double fit_max_before = 0;   //!< contour fit: largest contour-sample distance to the mesh before it (mm)
  double fit_max_after = 0;    //!< the same after it (equal to fit_max_before when nothing moved)
  bool redone = false;         //!< the frame was done again (a triangle angle below 25°, under 85 % of its angles
                               //!< in 40–80° or crossing triangles after the first try)
  double projection_max = 0;   //!< max distance (mm) from the frame's surface before the final projection
  double projection_mean = 0;  //!< mean of the same
};

//! What morph_sequence did.
struct MorphReport {
  std::vector<MorphFrameReport> frames;
  std::vector<SliceEvent> events;
  std::vector<SubMeshLifetime> submeshes;
};

//! Carries `frame0` (a closed mesh through frame 0's contours) through every frame of `seq`.
//! `surfaces[t]` is frame t's own surface (needed by RbfProject; may be empty for Rbf).
//! \throw SolverError when a frame cannot be fitted.
MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0, const std::vector<TriangleMesh>& surfaces,
                            const MorphOptions& options = {}, MorphReport* report = nullptr);

//! The same, with frame t's own surface given by `surface(t)` when it is first needed (RbfProject; Rbf needs
//! none); called from the calling thread only, frames in increasing order.
MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0,
                            const std::function<const TriangleMesh&(std::size_t)>& surface,
                            const MorphOptions& options = {}, MorphReport* report = nullptr);

//! Sub-mesh lifetimes from the contour counts of each slice over the frames.
std::vector<SubMeshLifetime> submesh_lifetimes(const Sequence& seq);

}  // namespace c4d
