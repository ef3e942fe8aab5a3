#pragma once
//! \file morph.h
//! \brief 4D morphing: the frame-0 mesh carried through every frame with the same vertices and
//! triangles (Lim et al., "4D Morphing of the Heart Model"; Miara et al. §III.E).

#include <functional>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/motion/contour_fit.h"
#include "contour4d/motion/vertical_deformation.h"
#include "contour4d/surface/angle_repair.h"

namespace c4d {

//! How a frame's mesh is obtained from the previous one.
enum class MorphMethod {
  Rbf,         //!< the paper: match mesh sections to the next contours, Hardy-multiquadric RBF in sub-steps
  RbfProject,  //!< default: the paper's RBF as a first guess, then a Laplacian-regularised projection onto the
               //!< frame's own reconstructed surface and tangential relaxation (exact fit, kept quality)
};

//! Options of the morphing stage.
struct MorphOptions {
  MorphMethod method = MorphMethod::RbfProject;  //!< see MorphMethod
  int rbf_steps = 10;              //!< RBF sub-steps against crossing paths (paper: 10); RbfProject uses 1
  int sources_per_contour = 48;    //!< chain points per matched contour used as RBF sources (Rbf)
  int guess_sources_per_contour = 24;  //!< the same for RbfProject's first-guess RBF: the projection and relaxation
                                       //!< refine the rest (48 gave the same meshes at 4× the RBF time)
  double threshold = 0.3;          //!< similarity for a chain↔contour match (paper: 30 %)
  double pin_spacing = 0.0;        //!< > 0: also hold frame-0 contour vertices on later contours, at least this ×
                                   //!< the median edge apart; 0: none held (they guide the RBF, the fit comes
                                   //!< from each frame's own surface; best triangles)
  double slide_spacing = 0.75;     //!< RbfProject: > 0: frame-0 contour vertices of a contour matched in the later frame
                                   //!< slide along that frame's contour (input polyline) through the relaxation and
                                   //!< the repair, at least this × the median edge apart along it (where the contour
                                   //!< shrank, the ones between relax on the surface); 0: none (they relax on the
                                   //!< surface, off the contour by up to the chordal error of the triangles)
  double slide_anisotropy = 1.1;   //!< chains beside a band whose height scaled more than this × its width (or its
                                   //!< width more than this × its height) since frame 0 do not slide: the band's
                                   //!< vertices must move through their planes to keep their triangles
  bool plane_snap = true;          //!< RbfProject: after the relaxation, on each edge crossing a matched contour's plane, the
                                   //!< endpoint nearest the plane goes onto the contour where its ring keeps its smallest
                                   //!< angle (or angle_repair.target_deg); mostly for slices whose chains were held
  int plane_snap_good_loss = -1;   //!< plane_snap: how many of the ring's angles in 40–80° a snap may lose (-1: any); 0 in a retry
  int plane_snap_relax_rounds = 1;  //!< plane_snap: relaxation rounds (relax_sweeps each) after the snap, each followed
                                    //!< by another snap (every try)
  std::size_t corner_candidates = 3;  //!< corner_angle_deg: how many of the nearest vertices on the contour are tried,
                                      //!< nearest first (1 in a retry). biv-me frame 5: conformity max 0.60 → 0.18 mm
  double corner_angle_deg = 30;    //!< a matched contour turning more than this at one of its points gets the nearest
                                   //!< vertex on it exactly there (as frame 0's resampled contours keep such corners)
  double retry_min_angle_deg = 25;  //!< a frame left with a triangle angle below this, fewer than retry_min_good_share
                                     //!< of its angles in 40–80° or crossing triangles is done again with no chain vertex
                                     //!< put on a contour and retry_sweep_factor × the relaxation rounds (each
                                     //!< relax_sweeps sweeps and a projection); the better is kept
  double retry_min_good_share = 0.85;  //!< see retry_min_angle_deg
  int retry_attempts = 1;          //!< tries after the first, each with twice the sweeps of the one before (the first
                                   //!< retry: retry_sweep_factor ×), until one meets the criteria; the best is kept
  int crossing_retry_attempts = 1;  //!< tries after retry_attempts while the best try still has crossing triangles
                                    //!< (each with twice the sweeps of the one before)
  int retry_sweep_factor = 8;      //!< see retry_min_angle_deg (biv-me frame 6: 61 → 0 triangles below 25°,
                                   //!< 78 → 85 % of angles in 40–80°; 6 gave 84.8 % with the plane snap)
  int projection_iterations = 3;   //!< regularised projection rounds (RbfProject); the relaxation re-projects
  double stiffness = 1.0;          //!< weight of the Laplacian term against the closest-point term
  int relax_iterations = 2;        //!< tangential relaxation rounds, each ended by an exact re-projection (4 gave
                                   //!< up to 2.6 points more of 40–80° for a fifth more time; morph.md, Relaxation)
  int relax_sweeps = 100;          //!< sweeps per round in the tangent planes (with momentum, as good as 1600
                                   //!< plain Jacobi sweeps)
  double relax_settled = 0.01;     //!< a relaxation round stops before relax_sweeps once no vertex moved more than this
                                   //!< × the median edge in its last sweep (0: always relax_sweeps). Not in a retry
                                   //!< (retry_min_angle_deg). Cycle phantoms 20–25 % faster, same quality (morph.md)
  double relax_step = 0.5;         //!< fraction of the tangential move per sweep
  bool vertical_deformation = false;  //!< Lim et al.'s sine vertical pre-deformation (eq. 10, Table 1) at slices whose
                                      //!< contours split or merge, before the matching (vertical_deformation.h)
  VerticalDeformationOptions vertical;  //!< its options
  int untangle_rounds = 4;         //!< RbfProject: where triangles intersect after the relaxation, rounds of umbrella
                                   //!< steps within the surface around them (0: off; see angle_repair.h untangle)
  AngleRepairOptions angle_repair{.passes = 8};  //!< after the relaxation (RbfProject): vertices of triangles with an
                                    //!< angle below angle_repair.target_deg move within the surface to maximise their
                                    //!< ring's smallest angle (passes = 0: off; 8 passes, not the surface's 4: the left
                                    //!< heart's ES saddle at edge 1 mm keeps 9 triangles below 25° with 4)
  bool contour_fit = true;         //!< RbfProject: last, a small smooth fit of the frame's mesh onto all its contours
                                   //!< where the surface cuts across them (contour_fit.h), kept where it adds no
                                   //!< crossing triangles and leaves no angle below fit_min_angle_deg that was
                                   //!< above it (angles it takes below retry_min_angle_deg are repaired within the
                                   //!< fitted surface first). The next frame starts from the mesh before the fit
  ContourFitOptions fit;           //!< its options
  double fit_min_angle_deg = 20;   //!< see contour_fit (25: biv-me frame 15 keeps 0.23 mm; 20: 0.13 mm, 3 triangles
                                   //!< below 25° in 25 frames)
  double fit_goal_mm = 0.2;        //!< a frame whose fit leaves a contour sample farther than this from the mesh is
                                   //!< fitted again from before the fit with fit_fallback_min_angle_deg, and the
                                   //!< closer result is kept
  double fit_fallback_min_angle_deg = 15;  //!< see fit_goal_mm (left-heart cycle, contours touching at the saddle:
                                           //!< 0.27 → 0.15 mm; a floor of 15 on every frame: biv-me frame 6 gets 16
                                           //!< triangles below 25°, against none)
  double relax_momentum = 0.9;     //!< heavy-ball momentum of the sweeps (0: plain Jacobi); speeds up the slow,
                                   //!< smooth modes about tenfold, so far fewer sweeps reach the same state
  double saddle_curvature = 0.05;  //!< relaxation, in the bands beside a slice whose contours split or merged since frame 0:
                                   //!< umbrella weights 1 + h / (this × median edge), h the edge's chord height over the
                                   //!< surface (from the normals at its ends), so edges across the saddle shorten and the
                                   //!< vertices gather where the surface bends (left heart ES: max distance to the truth
                                   //!< 0.98 → 0.38 mm); 0: off. Not used in a retry (retry_min_angle_deg)
  int sweep_lanes = 0;             //!< relaxation: vertices per step of a sweep (SIMD lanes): 0 the widest the CPU runs
                                   //!< (4 with AVX, else 2), 1, 2 or 4 (4 without AVX: 2); the result is the same bit
                                   //!< for bit (each lane repeats the one-vertex step's operations; tested), the time not
  double spring_weight = 0.0;      //!< relaxation: share of springs (frame-0 edge lengths) against the umbrella
  double shape_weight = 0.5;       //!< relaxation: share of the equilateral pull (each triangle draws the vertex towards
                                   //!< the apex of the equilateral triangle on its opposite edge) against the umbrella;
                                   //!< undoes the anisotropy that contraction leaves and the umbrella keeps
                                   //!< (uniform Laplacian); springs keep frame 0's shapes but can tangle
  bool biharmonic = false;         //!< RbfProject: a frame whose every slice keeps frame t−1's contours (the same count,
                                   //!< each matched one-to-one by the similarity index) is frame t−1's mesh plus the
                                   //!< thin-plate displacement (Σ|L d|² minimal, uniform Laplacian) that puts the mesh's
                                   //!< section on each slice plane onto frame t's contours (through the Fig. 7 match of
                                   //!< frame t−1's contour, along frame t's contour between targets): one sparse LDLᵀ,
                                   //!< reused while the section's edges do not change, instead of a projection and
                                   //!< relaxation; then the contour fit (contour_fit). A frame that then is farther than
                                   //!< fit_goal_mm from a contour sample, has an angle below retry_min_angle_deg, fewer
                                   //!< than retry_min_good_share of its angles in 40–80° or crossing triangles is done
                                   //!< the standard way. Off by default: no faster overall (frames that fail the guard
                                   //!< are done twice) and smaller smallest angles (docs/algorithms/morph.md)
};

//! A 2D contour topology change on one slice between two frames.
struct SliceEvent {
  int frame = 0;       //!< the later frame
  int slice = 0;       //!< slice id
  std::string kind;    //!< "split", "merge", "appear", "vanish" or "change"
  int before = 0;      //!< contours (mesh section loops) on the slice in the earlier frame
  int after = 0;       //!< contours on the slice in the later frame
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
  int matched = 0;             //!< section↔contour matches used as RBF constraints
  int sources = 0;             //!< RBF source points
  std::size_t intersecting_pairs = 0;  //!< triangle pairs still intersecting after untangling (RbfProject)
  std::size_t angle_repairs = 0;  //!< vertex moves of the small-angle repair
  std::size_t sliding = 0;     //!< contour-chain vertices kept on their contour (MorphOptions::slide_spacing)
  int plane_snapped = 0;       //!< vertices put on a contour by MorphOptions::plane_snap
  std::size_t fit_moved = 0;   //!< vertices moved by MorphOptions::contour_fit (0: none, or no harmless fit)
  double fit_max_before = 0;   //!< contour_fit: largest contour-sample distance to the mesh before it (mm)
  double fit_max_after = 0;    //!< the same after it (equal to fit_max_before when nothing moved)
  bool redone = false;         //!< the frame was done again (MorphOptions::retry_min_angle_deg)
  bool biharmonic = false;     //!< the frame is the previous one plus a biharmonic displacement (MorphOptions::biharmonic)
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

//! The same, with frame t's own surface given by `surface(t)` when it is first needed (MorphOptions::biharmonic
//! frames need none); called from the calling thread only, frames in increasing order.
MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0,
                            const std::function<const TriangleMesh&(std::size_t)>& surface, const MorphOptions& options = {},
                            MorphReport* report = nullptr);

//! Sub-mesh lifetimes from the contour counts of each slice over the frames.
std::vector<SubMeshLifetime> submesh_lifetimes(const Sequence& seq);

}  // namespace c4d
