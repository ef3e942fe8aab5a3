#pragma once
//! \file renderer.h
//! \brief Headless OpenGL playback of a 4D mesh (Miara et al. §IV, Table II): an EGL context without
//! a window (Mesa's llvmpipe where there is no GPU), two ways to animate the same scene, PNG output.
//!
//!  - classical: each frame's full mesh (positions and triangles) is sent with glBufferSubData;
//!  - compact: frame-0 positions, the control-vertex weights and the control displacements of all
//!    frames are uploaded once (temporal/compact.h); per frame only a uniform with the time is set and
//!    the vertex shader interpolates between frames on the GPU (linear or periodic Catmull-Rom).
//! Shading: Lambert with a headlight, flat normals from screen-space derivatives, same in both.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/render/patch_renderer.h"
#include "contour4d/temporal/compact.h"
#include "contour4d/temporal/interpolate.h"

namespace c4d {

//! An RGBA8 image, rows top to bottom.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
};

//! Camera and image options.
struct RenderOptions {
  int width = 640;                        //!< image width (pixels)
  int height = 480;                       //!< image height (pixels)
  Vec3 view_direction{-0.4, 1.0, -0.3};   //!< direction the camera looks along (LPS: from anterior, oblique)
  bool perspective = false;               //!< perspective instead of orthographic
  float color[3] = {0.85f, 0.25f, 0.2f};  //!< surface colour (RGB, 0..1)
  TimeInterpolation interpolation = TimeInterpolation::Linear;  //!< compact path between frames
};

//! An offscreen OpenGL 4.3 core context (EGL surfaceless or device platform) with a framebuffer.
class OffscreenRenderer {
 public:
  //! \throw Error (Internal) with a message naming the failing EGL/GL step and a hint
  //! (LIBGL_ALWAYS_SOFTWARE=1, EGL_PLATFORM=surfaceless, Mesa packages).
  explicit OffscreenRenderer(const RenderOptions& options = {});
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  //! GL_RENDERER and GL_VERSION strings of the context.
  std::string description() const;

  //! Classical path: keeps the frames on the CPU; draw_classical uploads frame f's mesh each call.
  void load_classical(const MeshSequence& seq);
  //! The same, with the camera fitted to `camera`'s frames instead (frames interpolated from `camera` drawn
  //! with the camera the compact path fits to the stored frames).
  void load_classical(const MeshSequence& seq, const MeshSequence& camera);
  //! Uploads frame `f` in full (glBufferSubData) and draws; returns the bytes uploaded.
  std::size_t draw_classical(std::size_t f);

  //! Compact path: uploads the decoded frame 0, weights and control motion once.
  void load_compact(const CompactModel& model);
  //! Draws the compact model at time t (ms): one uniform set; returns the bytes uploaded (the uniform).
  std::size_t draw_compact(double t_ms);

  //! Tessellation path: the pipeline of the viewer (render/patch_renderer.h) in this context; load
  //! it with patches().load(...) once, then draw_patches per frame.
  PatchRenderer& patches();
  //! Draws through the tessellation shaders into the offscreen framebuffer (the state's viewport
  //! is set to the image size). Returns the bytes uploaded (uniforms).
  std::size_t draw_patches(PatchDrawState state);

  //! Waits for the GPU and reads the framebuffer.
  Image read_image();
  //! Blocks until all drawing is done (for timing).
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

//! Writes an RGBA image as PNG. \throw IoError (OutputNotWritable).
void write_png(const std::filesystem::path& path, const Image& image);

}  // namespace c4d
