#pragma once
//! \file rebuild.h
//! \brief All frames, each its own surface on one mesh (Miara et al. §III.D: one base mesh, per-frame
//! geometry; Lim et al. 2014's one-frame surface in every frame): one frame's surface plan (surface_plan.h)
//! followed by every frame's contours. Where a frame's contours keep the plan frame's topology (the same
//! slices, contours per slice, nesting and links), it is built from its own contours with the plan's counts
//! and triangles: the same mesh by construction, no frame waiting for another, so the frames run in parallel
//! and the output does not depend on the thread count. The plan frame is, of the frames whose slices hold as
//! many contours as frame 0's, the one whose total contour length is the median (the others stretch or squeeze
//! its triangles by at most half the cycle's range). A frame that does not fit, or whose plan mesh lies off its
//! own surface or is squeezed, is left to the caller (reconstruct4d.h carries it).

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/surface/reconstruct.h"

namespace c4d {

//! What rebuild_frames did.
struct RebuildReport {
  int plan_frame = 0;                  //!< the frame whose surface plan every frame is built on
  std::string why_not;                 //!< why the plan is unusable or held no frame (empty: it was used)
  std::vector<int> unfit;              //!< frames whose contours do not fit the plan (another topology)
  std::vector<std::string> unfit_why;  //!< for each of them, what differs
};

//! Every frame of `seq` built on the plan frame's plan (reconstruct_frame_on_plan), in parallel, its free vertices
//! then moved onto the frame's own one-frame surface (a discretisation's difference, a tenth of a mm). Frames
//! whose contours do not fit the plan are left without positions (an empty vector) and listed in `report`;
//! std::nullopt when the plan itself is unusable or no frame holds on it. `surfaces`, when given, receives each
//! frame's SurfaceReport; `progress(done, total)` is called from worker threads as frames finish.
//! \throw InvalidInput naming the lowest frame whose surface failed.
std::optional<MeshSequence> rebuild_frames(const Sequence& seq, const SurfaceOptions& options,
                                           RebuildReport* report = nullptr,
                                           std::vector<SurfaceReport>* surfaces = nullptr,
                                           const std::function<void(int done, int total)>& progress = {});

}  // namespace c4d
