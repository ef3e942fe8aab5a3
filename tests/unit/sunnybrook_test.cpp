// Sunnybrook contours on DICOM images: patient-space placement, frames, nesting, bad input.
#include "contour4d/io/sunnybrook.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <unistd.h>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

namespace fs = std::filesystem;

fs::path patient() {
  const fs::path p = fs::path(C4D_DATA_DIR) / "sunnybrook-SC-HF-I-1";
  if (!fs::is_directory(p))
    ADD_FAILURE() << "the real data folder " << p << " is missing (see ../shared/data/README.md)";
  return p;
}

template <typename F>
ErrorCode code_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  ADD_FAILURE() << "no error thrown";
  return ErrorCode::Internal;
}

bool inside(const std::vector<Vec2>& poly, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
        p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
      in = !in;
  return in;
}

TEST(Sunnybrook, EndocardiumTwoPhasesNineSlicesInPatientSpace) {
  const fs::path dir = patient();
  ASSERT_TRUE(is_sunnybrook_folder(dir));
  const InputResult r = read_sunnybrook(dir);
  const Sequence& s = r.sequence;
  EXPECT_EQ(r.format, "sunnybrook");
  EXPECT_EQ(s.space, "LPS");
  ASSERT_EQ(s.frames.size(), 2u);                       // phases 7 and 18
  EXPECT_LT(s.frames[0].time_ms, s.frames[1].time_ms);  // TriggerTime, ms
  EXPECT_NEAR(s.frames[1].time_ms, 720.8, 30.0);        // image 59: 720.78 ms
  std::map<int, double> offset;
  for (const Frame& f : s.frames) {
    EXPECT_EQ(f.slices.size(), 9u);
    for (const Slice& sl : f.slices) {
      ASSERT_EQ(sl.contours.size(), 1u);
      EXPECT_EQ(sl.contours[0].label, "lv-endo");
      // The same slice id is the same plane in both phases.
      if (offset.count(sl.id)) {
        EXPECT_NEAR(offset[sl.id], sl.offset, 1e-3);
      }
      offset[sl.id] = sl.offset;
    }
  }
  // Slices (N - 1) div 20 = 2, 3, ..., 10, one every 10 mm along the normal, in id order.
  ASSERT_EQ(offset.size(), 9u);
  double prev = NAN;
  int sign = 0;
  for (const auto& [id, off] : offset) {
    if (!std::isnan(prev)) {
      EXPECT_NEAR(std::abs(off - prev), 10.0, 0.05) << "slice " << id;
      const int sg = off > prev ? 1 : -1;
      if (sign) {
        EXPECT_EQ(sg, sign);
      }
      sign = sg;
    }
    prev = off;
  }
  // Image 48 (phase 7, slice 2), first point (120.5, 137.5), by hand from its header:
  // IPP (176.111, 22.2895, 137.999), X (-0.104592, 0.346381, -0.932245),
  // Y (-0.733192, -0.660188, -0.163037), PixelSpacing 1.367188.
  const double d = 1.367188;
  const Vec3 X{-0.104592, 0.346381, -0.932245}, Y{-0.733192, -0.660188, -0.163037};
  const Vec3 expect = Vec3{176.111, 22.2895, 137.999} + (120.5 * d) * X + (137.5 * d) * Y;
  double best = 1e300;
  for (const Slice& sl : s.frames[0].slices)
    if (sl.id == 2)
      for (const Vec3& p : sl.contours[0].points) best = std::min(best, distance(p, expect));
  EXPECT_LT(best, 1e-6);
  // The stack normal is the image normal X × Y.
  EXPECT_NEAR(std::abs(dot(s.normal, normalized(cross(X, Y)))), 1.0, 1e-5);
}

TEST(Sunnybrook, EndocardiumInsideEpicardiumOnEverySlice) {
  SunnybrookOptions o;
  o.contours = SunnybrookContours::Both;
  const Sequence s = read_sunnybrook(patient(), o).sequence;
  int checked = 0;
  for (const Frame& f : s.frames)
    for (const Slice& sl : f.slices) {
      const Contour* endo = nullptr;
      const Contour* epi = nullptr;
      for (const Contour& c : sl.contours) (c.label == "lv-endo" ? endo : epi) = &c;
      if (!endo || !epi) continue;
      const Plane pl = slice_plane(s, sl);
      std::vector<Vec2> outer;
      for (const Vec3& p : epi->points) {
        EXPECT_LT(std::abs(signed_distance(pl, p)), 0.05);
        outer.push_back(to_plane(pl, p));
      }
      // As drawn, the basal slice's endocardium touches the epicardium: a few points lie on it or up
      // to half a pixel (0.68 mm) outside. Every point must be inside or within 0.75 mm of it.
      int out = 0;
      double worst = 0;
      for (const Vec3& p : endo->points) {
        const Vec2 q = to_plane(pl, p);
        if (inside(outer, q)) continue;
        ++out;
        double d = 1e300;
        for (std::size_t i = 0; i < outer.size(); ++i) {
          const Vec2 a = outer[i], b = outer[(i + 1) % outer.size()];
          const double t = std::clamp(dot(q - a, b - a) / std::max(1e-300, dot(b - a, b - a)), 0.0, 1.0);
          d = std::min(d, norm(q - (a + t * (b - a))));
        }
        worst = std::max(worst, d);
      }
      EXPECT_LT(worst, 0.75) << "slice " << sl.id;
      EXPECT_LE(out, static_cast<int>(endo->points.size()) / 5) << "slice " << sl.id;
      if (out)
        std::printf("[ figure ] slice %d: %d of %zu endocardial points on/outside the epicardium, by <= %.3f mm\n",
                    sl.id, out, endo->points.size(), worst);
      ++checked;
    }
  EXPECT_EQ(checked, 9);
  o.contours = SunnybrookContours::Epicardium;
  const Sequence epi = read_sunnybrook(patient(), o).sequence;
  ASSERT_EQ(epi.frames.size(), 1u);
  EXPECT_EQ(epi.frames[0].slices[0].contours[0].label, "lv-epi");
  o.contours = SunnybrookContours::Endocardium;
  o.space = "RAS";
  const Sequence ras = read_sunnybrook(patient(), o).sequence;
  const Sequence lps = read_sunnybrook(patient()).sequence;
  const Vec3 a = lps.frames[0].slices[0].contours[0].points[0], b = ras.frames[0].slices[0].contours[0].points[0];
  EXPECT_DOUBLE_EQ(a.x, -b.x);
  EXPECT_DOUBLE_EQ(a.y, -b.y);
}

TEST(SunnybrookBadInput, MissingImageMalformedLineMissingFolder) {
  const fs::path src = patient();
  const fs::path dir = fs::temp_directory_path() / ("c4d_sunnybrook_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "i-contours");
  fs::create_directories(dir / "dicoms_contoured");
  fs::copy_file(src / "i-contours" / "IM-0001-0048-icontour-manual.txt",
                dir / "i-contours" / "IM-0001-0048-icontour-manual.txt");
  EXPECT_EQ(code_of([&] { read_sunnybrook(dir); }), ErrorCode::MissingCompanion);
  fs::copy_file(src / "dicoms_contoured" / "48.dcm", dir / "dicoms_contoured" / "48.dcm");
  EXPECT_EQ(read_sunnybrook(dir).sequence.frames.size(), 1u);
  std::ofstream(dir / "i-contours" / "IM-0001-0048-icontour-manual.txt", std::ios::app) << "12.5 oops\n";
  EXPECT_EQ(code_of([&] { read_sunnybrook(dir); }), ErrorCode::Parse);
  std::ofstream(dir / "dicoms_contoured" / "48.dcm") << "not a dicom";
  fs::copy_file(src / "i-contours" / "IM-0001-0048-icontour-manual.txt",
                dir / "i-contours" / "IM-0001-0048-icontour-manual.txt", fs::copy_options::overwrite_existing);
  EXPECT_EQ(code_of([&] { read_sunnybrook(dir); }), ErrorCode::Parse);
  EXPECT_EQ(code_of([&] { read_sunnybrook(dir / "nope"); }), ErrorCode::FileNotFound);
  fs::remove_all(dir / "i-contours");
  EXPECT_EQ(code_of([&] { read_sunnybrook(dir); }), ErrorCode::FileNotFound);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace c4d
