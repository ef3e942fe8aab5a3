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
#include "contour4d/motion/rebuild.h"
#include "contour4d/surface/reconstruct.h"

namespace c4d {

//! How frames after 0 are built.
enum class AllFramesMethod {
  Auto,     //!< Rebuild where the contours keep their topology through the cycle, Morph otherwise
  Rebuild,  //!< every frame its own surface on frame 0's plan (rebuild.h); refused where topology changes
  Carry,    //!< every frame on its own from frame 0's mesh onto the frame's own surface (carry.h): in parallel
  Morph,    //!< frame after frame, each from the one before (morph.h; MorphOptions::method picks the paper's RBF)
};

//! Options of the 4D reconstruction.
struct Reconstruct4DOptions {
  AllFramesMethod all_frames = AllFramesMethod::Auto;  //!< the all-frames stage
  CarryOptions carry;                                  //!< AllFramesMethod::Carry
  SurfaceOptions surface;  //!< the one-frame surface. Frame 0's, the carried mesh, is built with remeshed bands
                           //!< (ours) and the morph's small-angle target (32°): it starts with even triangles
                           //!< where the morph keeps them; the later frames' surfaces are projection targets
                           //!< (SurfaceOptions::geometry_only)
  MorphOptions morph;      //!< the deformation through the frames
  std::function<void(const char* stage, int done, int total)> progress;  //!< optional progress callback
};

//! What reconstruct_4d did.
struct Reconstruct4DReport {
  std::vector<SurfaceReport> surfaces;  //!< per frame (the frame's own surface)
  MorphReport morph;      //!< AllFramesMethod::Carry fills its frames' matched counts, events and sub-meshes
  CarryReport carry;      //!< AllFramesMethod::Carry
  RebuildReport rebuild;  //!< AllFramesMethod::Auto and Rebuild: why the frames were not rebuilt, if they were not
  AllFramesMethod used = AllFramesMethod::Morph;  //!< the stage that made the result (Rebuild, Carry or Morph)
};

//! Builds the 4D mesh of `seq` (one label). Frames' own surfaces are built by TBB tasks in frame order
//! while the morph runs (it waits only for the frame it needs next);
//! the result does not depend on the thread count.
//! \throw InvalidInput / SolverError naming the frame that failed (the lowest one if several did).
MeshSequence reconstruct_4d(const Sequence& seq, const Reconstruct4DOptions& options = {},
                            Reconstruct4DReport* report = nullptr);

}  // namespace c4d
