#pragma once
//! \file viewer.h
//! \brief The interactive window of `contour4d view` (GLFW, OpenGL 4.3 core): the pipeline of
//! render/patch_renderer.h with playback controls. It shows the decoded frames as `contour4d render`
//! draws them, with an overlay (time, frame, volume, the volume curve, the keys; a message while the
//! patches are built). Keys (kViewerKeys): space play/pause, left/right one frame, +/- speed,
//! T tessellated patches (built on first use), [ ] their level, D their maps on/off, H overlay,
//! W wireframe, S section plane with the input contours, , . move the section by one slice,
//! I interpolation (linear / periodic Catmull-Rom), R reset view, Esc/Q quit; left drag orbits,
//! wheel zooms. The title shows the frames per second.

#include <string>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/render/patch_renderer.h"
#include "contour4d/temporal/displacement_map.h"

namespace c4d {

//! Options of run_viewer.
struct ViewerOptions {
  int width = 1280;                      //!< window size (pixels)
  int height = 800;                      //!< window size (pixels)
  double speed = 1.0;                    //!< playback speed (1: real time of the frames' time_ms)
  PatchDrawState initial;                //!< first state shown (level, interpolation, section...)
  std::string title = "contour4d view";  //!< window title prefix
  int max_seconds = 0;                   //!< close after this many seconds (0: never; for smoke tests)
  PatchOptions patches;                  //!< how the tessellated patches are built (key T)
};

//! The keys, as the overlay's footer shows them.
inline constexpr const char* kViewerKeys =
    "space play  <- -> frame  +/- speed  T patches  H overlay  W wire  S section  , . slice  I interp  R reset  Q quit";

//! True when this build has the window (GLFW found at configure time).
bool viewer_available();

//! Opens the window and plays `frames` (a 4D mesh, e.g. a decoded model.c4d) until it is closed.
//! `contours` may be null. \throw Error (NotImplemented) when built without GLFW, or when no display or
//! no OpenGL 4.3 context can be opened, with a hint (DISPLAY, `contour4d view --snapshot` headless).
void run_viewer(const MeshSequence& frames, const Sequence* contours, const ViewerOptions& options = {});

}  // namespace c4d
