#pragma once
//! \file reconstruct4d.h
//! \brief The whole pipeline (Lim et al. Fig. 1): contours of every frame → frame-0 surface →
//! morphed through all frames with 1-to-1 vertex correspondence.

#include <functional>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/motion/carry.h"
#include "contour4d/motion/morph.h"
#include "contour4d/surface/reconstruct.h"

namespace c4d {

//! How frames after 0 are built.
enum class AllFramesMethod {
  Carry,  //!< every frame on its own from frame 0's mesh onto the frame's own surface (carry.h): in parallel
  Morph,  //!< frame after frame, each from the one before (morph.h; MorphOptions::method picks the paper's RBF)
};

//! Options of the 4D reconstruction.
struct Reconstruct4DOptions {
  AllFramesMethod all_frames = AllFramesMethod::Morph;  //!< the all-frames stage
  CarryOptions carry;      //!< AllFramesMethod::Carry
  SurfaceOptions surface;  //!< the one-frame surface (frame 0, and each frame's target for RbfProject); frame 0's
                           //!< small-angle repair aims at morph.angle_repair.target_deg (32°) instead of
                           //!< surface.angle_repair's (28°): the carried mesh starts where the morph keeps it
  MorphOptions morph;      //!< the deformation through the frames
  bool fast_targets = true;   //!< frames after 0 only give geometry (frame 0's triangles are carried):
                              //!< build their surfaces with interpolated rows (SurfaceOptions::rows) and
                              //!< without the self-intersection test (not reported)
  int fast_target_repair_passes = 0;  //!< fast_targets: small-angle repair passes on those surfaces (0: none;
                                      //!< the morph repairs its own triangles). With 8: left-heart cycle 9 %
                                      //!< and biv-me 28 % slower on 2 threads, biv-me's worst frame 86.9 →
                                      //!< 88.8 % of angles in 40–80° (morph.md, Speed)
  bool frame0_rows = false;   //!< frame 0 by SurfaceOptions::rows too; false: by the remeshed bands path, whose
                              //!< isotropic remeshing spreads the vertices that the morph carries through the
                              //!< cycle evenly (with rows the left heart's ES frame keeps 86.6 % of its angles in
                              //!< 40–80°, against 95.4 %; morph.md)
  RemeshEngine frame0_remesher = RemeshEngine::Fast;  //!< !frame0_rows: the remeshing of frame 0's bands (replaces
                                                     //!< surface.remesher there). Ours against CGAL's: faster, a
                                                     //!< larger share of angles in 40–80° in every input's worst
                                                     //!< frame but the bifurcation's (91.7 against 92.1 %); min
                                                     //!< angles and conformity move both ways (morph.md)
  std::function<void(const char* stage, int done, int total)> progress;  //!< optional progress callback
};

//! What reconstruct_4d did.
struct Reconstruct4DReport {
  std::vector<SurfaceReport> surfaces;  //!< per frame (the frame's own surface)
  MorphReport morph;  //!< AllFramesMethod::Carry fills its frames' matched counts, events and sub-meshes
  CarryReport carry;  //!< AllFramesMethod::Carry
};

//! Builds the 4D mesh of `seq` (one label). Frames' own surfaces are built by TBB tasks in frame order
//! while the morph runs (it waits only for the frame it needs next);
//! the result does not depend on the thread count.
//! \throw InvalidInput / SolverError naming the frame that failed (the lowest one if several did).
MeshSequence reconstruct_4d(const Sequence& seq, const Reconstruct4DOptions& options = {},
                            Reconstruct4DReport* report = nullptr);

}  // namespace c4d
