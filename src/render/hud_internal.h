#pragma once
// The on-screen information of `contour4d view` and its snapshots, drawn over the scene in pixel
// coordinates: lines of text at the top left, a footer (the keys) at the bottom left, and the volume
// curve of the cycle at the bottom right with the current time marked. Text from stb_easy_font
// (Debian's libstb-dev). Private to src/render.
#include <memory>
#include <string>
#include <vector>

#include "gl_util_internal.h"

namespace c4d {

//! What the overlay shows.
struct HudContent {
  std::vector<std::string> lines;  //!< top left, one per line
  std::string footer;              //!< bottom left
  std::vector<double> times_ms;    //!< the curve's frame times
  std::vector<double> volumes_ml;  //!< the volume of each frame (empty: no curve)
  double t_ms = 0.0;               //!< the time marked on the curve
};

//! GL objects of the overlay (the context must be current while it lives).
class Hud {
 public:
  explicit Hud(const GlFailure& failure);
  ~Hud();
  Hud(const Hud&) = delete;
  Hud& operator=(const Hud&) = delete;
  //! Draws over the bound framebuffer of `width` x `height` pixels (depth test off while it draws).
  void draw(const HudContent& content, int width, int height);

 private:
  GLuint prog_ = 0, vao_ = 0, vbo_ = 0;
};

}  // namespace c4d
