#pragma once
//! \file rebuild.h
//! \brief All frames, each its own surface on one mesh (Miara et al. §III.D: one base mesh, per-frame
//! geometry; Lim et al. 2014's one-frame surface in every frame): frame 0's surface plan (surface_plan.h)
//! followed by every frame's contours. Where the contours keep their topology through the cycle (the same
//! slices, contours per slice, nesting and links in every frame), each frame is built from its own contours
//! with frame 0's counts and triangles: the same mesh by construction, no frame waiting for another, so the
//! frames run in parallel and the output does not depend on the thread count.

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
  std::string why_not;                 //!< why frame 0's plan is unusable (empty: it was used)
  std::vector<int> unfit;              //!< frames whose contours do not fit the plan (another topology)
  std::vector<std::string> unfit_why;  //!< for each of them, what differs
};

//! Every frame of `seq` built on frame 0's plan (reconstruct_frame_on_plan), in parallel, its free vertices
//! then moved onto the frame's own one-frame surface (a discretisation's difference, a tenth of a mm). Frames
//! whose contours do not fit the plan are left without positions (an empty vector) and listed in `report`;
//! std::nullopt when the plan itself is unusable. `surfaces`, when given, receives each frame's
//! SurfaceReport; `progress(done, total)` is called from worker threads as frames finish.
//! \throw InvalidInput naming the lowest frame whose surface failed.
std::optional<MeshSequence> rebuild_frames(const Sequence& seq, const SurfaceOptions& options,
                                           RebuildReport* report = nullptr,
                                           std::vector<SurfaceReport>* surfaces = nullptr,
                                           const std::function<void(int done, int total)>& progress = {});

}  // namespace c4d
