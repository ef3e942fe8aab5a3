// Headless rendering: an EGL context must come up (llvmpipe without a GPU; the test FAILS, never
// skips, when it cannot), the object covers the image centre, frames differ over time, and the
// classical and compact paths draw the same picture.
#include "contour4d/render/renderer.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include "contour4d/temporal/compact.h"
#include "contour4d/temporal/sequence.h"

// Under ASan: Mesa unloads its driver (swrast_dri.so) at eglTerminate, so the few hundred bytes it
// keeps show as leaks in an "<unknown module>" that no LSan suppression can name (tests/lsan.supp
// covers the loaded driver frames). Leak checking is therefore off in this one test binary; the
// library's own code is leak-checked by the other tests.
extern "C" const char* __asan_default_options() { return "detect_leaks=0"; }  // NOLINT

namespace c4d {
namespace {

bool is_object(const Image& im, int x, int y) {
  const std::uint8_t* p = im.rgba.data() + (static_cast<std::size_t>(y) * im.width + x) * 4;
  return !(p[0] == 255 && p[1] == 255 && p[2] == 255);
}

double object_fraction(const Image& im) {
  std::size_t n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) n += is_object(im, x, y);
  return static_cast<double>(n) / (im.width * im.height);
}

std::unique_ptr<OffscreenRenderer> make(const RenderOptions& o) {
  try {
    return std::make_unique<OffscreenRenderer>(o);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "cannot create a headless OpenGL context: " << e.what()
                  << "\nThis test needs EGL + Mesa (llvmpipe): LIBGL_ALWAYS_SOFTWARE=1 EGL_PLATFORM=surfaceless";
    return nullptr;
  }
}

TEST(Render, CompactAndClassicalDrawTheBeatingShape) {
  RenderOptions o;
  o.width = 160;
  o.height = 120;
  auto r = make(o);
  ASSERT_NE(r, nullptr);
  const MeshSequence seq = synthetic_beating_mesh(3, 8);
  const CompactModel model = compact_encode(seq);
  r->load_compact(model);
  std::vector<Image> images;
  for (std::size_t f = 0; f < seq.positions.size(); ++f) {
    EXPECT_LE(r->draw_compact(seq.times_ms[f]), 64u);  // per-frame upload: uniforms only
    images.push_back(r->read_image());
  }
  for (const Image& im : images) {
    EXPECT_TRUE(is_object(im, o.width / 2, o.height / 2));  // centre covered
    EXPECT_FALSE(is_object(im, 0, 0));                       // corner is background
    const double frac = object_fraction(im);
    EXPECT_GT(frac, 0.1);
    EXPECT_LT(frac, 0.9);
  }
  // Diastole (frame 0) covers more pixels than end-systole (~35 % of the cycle).
  EXPECT_GT(object_fraction(images[0]), object_fraction(images[3]) * 1.05);
  EXPECT_NE(images[0].rgba, images[3].rgba);

  // Classical path, same scene: nearly the same pixels.
  r->load_classical(compact_decode(model));
  EXPECT_GT(r->draw_classical(3), 1000u);
  const Image c = r->read_image();
  std::size_t differ = 0;
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) differ += is_object(c, x, y) != is_object(images[3], x, y);
  EXPECT_LT(static_cast<double>(differ) / (o.width * o.height), 0.01);
}

}  // namespace
}  // namespace c4d
