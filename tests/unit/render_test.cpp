// Headless rendering: an EGL context must come up (llvmpipe without a GPU; the test FAILS, never
// skips, when it cannot), the object covers the image centre, frames differ over time, and the
// classical and compact paths draw the same picture.
#include "contour4d/render/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "contour4d/core/errors.h"
#include "contour4d/motion/reconstruct4d.h"
#include "contour4d/phantoms/phantom.h"
#include "contour4d/render/viewer.h"
#include "contour4d/temporal/compact.h"
#include "contour4d/temporal/displacement_map.h"
#include "contour4d/temporal/sequence.h"
#include "temporal_fixtures.h"

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

// The image size of the beating-shape tests: small, so that software rendering stays quick.
RenderOptions small_image() {
  RenderOptions o;
  o.width = 160;
  o.height = 120;
  return o;
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
  const RenderOptions o = small_image();
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
    EXPECT_FALSE(is_object(im, 0, 0));                      // corner is background
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

// What a user sees: the default (compact) path and the classical path draw the same reconstruction of the
// 20-frame left-heart cycle alike, frame by frame. Mean grey difference under 2 levels, and no crack lines:
// at most a few pixels inside the object (2 pixels in from any silhouette) differ by more than 24 grey
// levels. The control-vertex model this path drew before failed the second check (16 such pixels in the
// worst frame of this cycle, 409 on biv-me's 25 frames; 2 now).
TEST(Render, CompactPathDrawsWhatTheClassicalPathDraws) {
  if (!C4D_HEAVY_TESTS) GTEST_SKIP() << "whole-pipeline test: release build only";
  const Phantom ph = make_phantom("left-heart-cycle", {});
  const MeshSequence seq = reconstruct_4d(ph.contours);
  RenderOptions o;  // 640 x 480, the size `contour4d render` draws
  auto r = make(o);
  ASSERT_NE(r, nullptr);
  std::vector<Image> classical;
  r->load_classical(seq);
  for (std::size_t f = 0; f < seq.positions.size(); ++f) {
    r->draw_classical(f);
    classical.push_back(r->read_image());
  }
  r->load_compact(compact_encode(seq));
  for (std::size_t f = 0; f < seq.positions.size(); ++f) {
    r->draw_compact(seq.times_ms[f]);
    const Image c = r->read_image();
    const Image& e = classical[f];
    const auto grey = [](const Image& im, int x, int y) {
      const std::uint8_t* p = im.rgba.data() + (static_cast<std::size_t>(y) * im.width + x) * 4;
      return (p[0] * 299 + p[1] * 587 + p[2] * 114) / 1000.0;
    };
    const auto inside = [&](int x, int y) {  // object in both images, 2 pixels in from every silhouette
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          if (!is_object(c, x + dx, y + dy) || !is_object(e, x + dx, y + dy)) return false;
      return true;
    };
    double sum = 0.0;
    std::size_t cracks = 0;
    for (int y = 0; y < o.height; ++y)
      for (int x = 0; x < o.width; ++x) {
        const double d = std::abs(grey(c, x, y) - grey(e, x, y));
        sum += d;
        if (d > 24.0 && x >= 2 && y >= 2 && x < o.width - 2 && y < o.height - 2 && inside(x, y)) ++cracks;
      }
    EXPECT_LT(sum / (o.width * o.height), 2.0) << "frame " << f;
    EXPECT_LE(cracks, 4u) << "frame " << f << ": pixels inside the object that differ by more than 24 grey levels";
  }
}

// The viewer's pipeline drawn headless: base mesh + displacement maps through the tessellation
// shaders. The object is where expected, frames differ over time, the tessellator amplifies the base
// mesh (at least level² triangles per patch), and wireframe / section change the picture.
TEST(Render, TessellatedPatchesDrawTheBeatingShape) {
  const RenderOptions o = small_image();
  auto r = make(o);
  ASSERT_NE(r, nullptr);
  const auto [seq, po, pm] = test::beating_patches(3, 8, 200, 4);
  ASSERT_GT(pm.triangles.size(), 50u);
  r->patches().load(pm);
  PatchDrawState st;
  st.level = 4;
  std::vector<Image> images;
  for (std::size_t f = 0; f < seq.positions.size(); ++f) {
    st.t_ms = seq.times_ms[f];
    EXPECT_LE(r->draw_patches(st), 64u);  // per-frame upload: uniforms only
    images.push_back(r->read_image());
  }
  for (const Image& im : images) {
    EXPECT_TRUE(is_object(im, o.width / 2, o.height / 2));
    EXPECT_FALSE(is_object(im, 0, 0));
    const double frac = object_fraction(im);
    EXPECT_GT(frac, 0.05);
    EXPECT_LT(frac, 0.9);
  }
  EXPECT_GT(object_fraction(images[0]), object_fraction(images[3]) * 1.05);  // diastole vs systole
  EXPECT_NE(images[0].rgba, images[3].rgba);
  PatchDrawState q = st;
  q.width = o.width;
  q.height = o.height;
  EXPECT_GE(r->patches().count_triangles(q), pm.triangles.size() * 16);
  q.level = 1;
  EXPECT_EQ(r->patches().count_triangles(q), pm.triangles.size());
  // Between two frames the picture lies between theirs (interpolated on the GPU).
  st.t_ms = 0.5 * (seq.times_ms[2] + seq.times_ms[3]);
  r->draw_patches(st);
  const double mid = object_fraction(r->read_image());
  EXPECT_LE(mid, std::max(object_fraction(images[2]), object_fraction(images[3])) + 1e-3);
  EXPECT_GE(mid, std::min(object_fraction(images[2]), object_fraction(images[3])) - 1e-3);
  st.t_ms = 0.0;
  st.wireframe = true;
  r->draw_patches(st);
  EXPECT_NE(r->read_image().rgba, images[0].rgba);
}

// An analytic phantom end to end: its contours reconstructed to a 4D mesh, then drawn through the
// tessellation pipeline with the section plane showing the input contours. The shrinking ellipsoid
// covers fewer pixels at mid-cycle; the section shows contour pixels (blue) over the cut.
TEST(Render, PhantomThroughTheTessellationPipeline) {
  PhantomOptions po;
  po.spacing = 8.0;
  po.frames = 4;
  po.truth_edge = 2.0;
  const Phantom ph = make_phantom("ellipsoid", po);
  Reconstruct4DOptions ro;
  ro.surface.edge = 2.5;
  const MeshSequence seq = reconstruct_4d(ph.contours, ro);
  PatchOptions pat;
  pat.base_triangles = 300;
  pat.grid = 4;
  const PatchMesh pm = build_patch_mesh(seq, pat);
  const RenderOptions o = small_image();
  auto r = make(o);
  ASSERT_NE(r, nullptr);
  r->patches().load(pm);
  r->patches().set_contours(ph.contours);
  EXPECT_GT(r->patches().slice_count(), 3u);
  PatchDrawState st;
  st.level = 3;
  std::vector<double> cover;
  std::vector<Image> images;
  for (std::size_t f = 0; f < seq.positions.size(); ++f) {
    st.t_ms = seq.times_ms[f];
    r->draw_patches(st);
    images.push_back(r->read_image());
    EXPECT_TRUE(is_object(images.back(), o.width / 2, o.height / 2)) << "frame " << f;
    EXPECT_FALSE(is_object(images.back(), 0, 0));
    cover.push_back(object_fraction(images.back()));
  }
  EXPECT_GT(cover[0], cover[2] * 1.05);  // 25x25x40 mm shrinking towards 19x19x30 at mid-cycle
  EXPECT_NE(images[0].rgba, images[2].rgba);
  st.t_ms = seq.times_ms[0];
  st.section = true;
  st.camera.yaw_deg = 90.0;  // look at the cut from the removed side
  r->draw_patches(st);
  const Image cut = r->read_image();
  std::size_t blue = 0;
  for (std::size_t i = 0; i < cut.rgba.size(); i += 4) blue += cut.rgba[i + 2] > 150 && cut.rgba[i] < 80;
  EXPECT_GT(blue, 20u);
}

// No display here: the window must fail with a c4d::Error naming what to do, never crash.
TEST(Viewer, WithoutDisplayThrowsAClearError) {
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  EXPECT_THROW(run_viewer(synthetic_beating_mesh(2, 4), nullptr, {}), Error);
}

// The viewer's pipeline as `view --snapshot` draws it: the decoded frames (the default) cover the image
// centre, the section clips them, and the overlay adds dark text at the top left and the volume curve
// (blue) with its time marker (red) at the bottom right.
TEST(Render, ViewerDrawsTheDecodedFramesWithItsOverlay) {
  const RenderOptions o = small_image();
  RenderOptions big = o;
  big.width = 480;
  big.height = 320;
  auto r = make(big);
  ASSERT_NE(r, nullptr);
  const MeshSequence seq = synthetic_beating_mesh(3, 8);
  r->patches().load_mesh(seq);
  PatchDrawState st;
  st.mesh = true;
  st.t_ms = seq.times_ms[3];
  r->draw_patches(st);
  const Image plain = r->read_image();
  EXPECT_TRUE(is_object(plain, big.width / 2, big.height / 2));
  EXPECT_FALSE(is_object(plain, 0, 0));
  st.section = true;
  r->draw_patches(st);
  EXPECT_LT(object_fraction(r->read_image()), object_fraction(plain));
  st.section = false;
  st.hud = true;
  st.hud_lines = {"status line"};
  st.hud_footer = kViewerKeys;
  r->draw_patches(st);
  const Image hud = r->read_image();
  const auto count = [&](const Image& im, int x0, int y0, int x1, int y1, auto pred) {
    std::size_t n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += pred(im.rgba.data() + (static_cast<std::size_t>(y) * big.width + x) * 4);
    return n;
  };
  const auto dark = [](const std::uint8_t* p) { return p[0] < 60 && p[1] < 60 && p[2] < 60; };
  const auto blue = [](const std::uint8_t* p) { return p[2] > 150 && p[0] < 80; };
  const auto red = [](const std::uint8_t* p) { return p[0] > 150 && p[1] < 60 && p[2] < 60; };
  EXPECT_EQ(count(plain, 0, 0, 200, 30, dark), 0u);
  EXPECT_GT(count(hud, 0, 0, 200, 30, dark), 50u);                                             // time line
  EXPECT_GT(count(hud, big.width - 180, big.height - 100, big.width, big.height, blue), 30u);  // curve
  EXPECT_GT(count(hud, big.width - 180, big.height - 100, big.width, big.height, red), 5u);    // marker
}

}  // namespace
}  // namespace c4d
