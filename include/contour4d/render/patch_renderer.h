#pragma once
//! \file patch_renderer.h
//! \brief The drawing pipeline shared by the window (`contour4d view`) and the offscreen renderer
//! (`contour4d view --snapshot`, `contour4d render --tessellated`): the decoded frames of the compact
//! model (what `contour4d render` draws by default: frame 0 and every frame's displacement uploaded
//! once, blended per time in the vertex stage), or a base mesh and its displacement maps
//! (temporal/displacement_map.h) through the tessellation stages; per frame only uniforms (time
//! weights, camera), and an optional overlay (time, frame, volume curve, keys). Miara et al. §III.E /
//! Table II.
//!
//! Per base triangle the tessellation control shader sets the level; the evaluation shader builds
//! the cubic PN patch from the corners and normals blended between frames (linear or periodic
//! Catmull-Rom weights), adds the displacement map (linear on its lattice, blended the same way)
//! along the patch normal, and clips by the section plane. A line program draws the input contours
//! of the slice nearest to the section plane.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/temporal/displacement_map.h"
#include "contour4d/temporal/interpolate.h"

namespace c4d {

//! Orbit camera about the centre of the model's bounding box; superior (+z) up.
struct OrbitCamera {
  double yaw_deg = -65.0;   //!< azimuth of the eye about +z; -90 looks from anterior (−y, LPS)
  double pitch_deg = 20.0;  //!< elevation of the eye (degrees, ±85)
  double zoom = 1.0;        //!< distance factor (< 1 closer)
};

//! What one draw call shows.
struct PatchDrawState {
  double t_ms = 0.0;       //!< time (ms); frames are blended per `interpolation`
  int level = 8;           //!< tessellation level, inner and outer (1..64): about 1.5·level² triangles per patch
  bool displaced = true;   //!< add the displacement maps (false: the smooth PN patches only)
  bool wireframe = false;  //!< draw the tessellated edges over the surface
  bool section = false;    //!< clip at the section plane and draw the contours of that slice
  int section_slice = -1;  //!< index into the sorted slice list (-1: the middle slice)
  bool mesh = false;       //!< draw the decoded frames (load_mesh) instead of the tessellated patches
  bool hud = false;        //!< draw the overlay: time and frame, `hud_lines`, the volume curve, `hud_footer`
  std::vector<std::string> hud_lines;  //!< extra lines under the time (e.g. playback state, frames/s)
  std::string hud_footer;              //!< bottom line (e.g. the keys)
  TimeInterpolation interpolation = TimeInterpolation::Linear;  //!< between frames
  OrbitCamera camera;                                           //!< view
  int width = 640;                                              //!< viewport (pixels)
  int height = 480;                                             //!< viewport (pixels)
  float color[3] = {0.85f, 0.25f, 0.2f};                        //!< surface colour (RGB, 0..1)
};

//! GL objects and programs of the pipeline. Construct, use and destroy with the same OpenGL 4.3+
//! core context current (tessellation shaders are core since 4.0).
class PatchRenderer {
 public:
  //! Compiles and links the programs. \throw Error (Internal) naming the failing shader and its log.
  PatchRenderer();
  ~PatchRenderer();
  PatchRenderer(const PatchRenderer&) = delete;
  PatchRenderer& operator=(const PatchRenderer&) = delete;

  //! Uploads the base triangles, corners and normals of all frames, and all displacement maps (once).
  //! \throw InvalidInput (BadMesh) on an empty patch mesh.
  void load(const PatchMesh& pm);
  //! Uploads the decoded frames (frame 0 and every frame's displacement, once) for PatchDrawState::mesh,
  //! and keeps each frame's volume for the overlay's curve. \throw InvalidInput (BadMesh) when empty.
  void load_mesh(const MeshSequence& frames);
  //! Uploads the input contours (all frames, once), for the section view.
  void set_contours(const Sequence& contours);
  //! Number of slices of the contours set (0 without contours).
  std::size_t slice_count() const;

  //! Draws into the bound framebuffer (clears it). Returns the bytes sent to the GPU for this frame
  //! (uniforms only).
  std::size_t draw(const PatchDrawState& state);
  //! Triangles the tessellator generated for `state` (a GL_PRIMITIVES_GENERATED query around draw).
  std::uint64_t count_triangles(const PatchDrawState& state);
  //! Bytes uploaded by load and set_contours.
  std::size_t static_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace c4d
