// Contours missing from some frames, filled in time (contour_gaps.h), on families with random seeds: ventricles
// contracting over a cycle, an inner slice's contour left out of random frames. The fill lies within 0.75 mm of
// the left-out contour whatever the start point and orientation of the contours around it; a slice at the end of
// the structure in that frame, or one with two contours (a ring), is left as it is.
#include "contour4d/core/contour_gaps.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "contour4d/core/contour.h"

namespace c4d {
namespace {

constexpr double kPi = std::numbers::pi;

// An elliptic section of slice k in frame f: radii contract by up to 25 % over the cycle; `start` and `reverse`
// set where the polygon starts and which way it runs.
Contour section(int k, int f, int frames, double z, int start, bool reverse) {
  const double squeeze = 1.0 - 0.25 * 0.5 * (1 - std::cos(2 * kPi * f / frames));
  const double a = squeeze * (18.0 + 2.0 * k), b = squeeze * (14.0 + 1.5 * k);
  Contour c{"lv-endo", k, {}};
  const int n = 40 + 3 * k;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * ((i + start) % n) / n * (reverse ? -1 : 1);
    c.points.push_back({a * std::cos(t) + 2.0 * std::sin(2 * kPi * f / frames), b * std::sin(t), z});
  }
  return c;
}

Sequence cycle(std::mt19937& rng, int slices, int frames) {
  std::uniform_int_distribution<int> start(0, 39);
  std::bernoulli_distribution flip(0.5);
  Sequence seq;
  for (int f = 0; f < frames; ++f) {
    Frame fr;
    fr.time_ms = 40.0 * f;
    for (int k = 0; k < slices; ++k) {
      const double z = 10.0 * k;
      fr.slices.push_back({k, z, {section(k, f, frames, z, start(rng), flip(rng))}});
    }
    seq.frames.push_back(fr);
  }
  return seq;
}

void remove_slice(Sequence& seq, int f, int id) {
  auto& s = seq.frames[static_cast<std::size_t>(f)].slices;
  s.erase(std::remove_if(s.begin(), s.end(), [&](const Slice& x) { return x.id == id; }), s.end());
}

const Contour* find(const Sequence& seq, int f, int id) {
  for (const Slice& s : seq.frames[static_cast<std::size_t>(f)].slices)
    if (s.id == id) return &s.contours.front();
  return nullptr;
}

// The largest distance from the fill's points to the true section, and the true section's to the fill.
double two_way(const Contour& a, const Contour& b) {
  std::vector<Vec2> pa, pb;
  for (const Vec3& p : a.points) pa.push_back({p.x, p.y});
  for (const Vec3& p : b.points) pb.push_back({p.x, p.y});
  double d = 0;
  for (const Vec2& p : pa) d = std::max(d, polyline_distance(p, pb));
  for (const Vec2& p : pb) d = std::max(d, polyline_distance(p, pa));
  return d;
}

TEST(ContourGaps, LeftOutContoursAreFilledCloseToTheTruth) {
  for (int seed = 0; seed < 30; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    const int slices = 4 + seed % 5, frames = 10 + seed % 16;
    Sequence seq = cycle(rng, slices, frames);
    const Sequence truth = seq;
    std::uniform_int_distribution<int> inner(1, slices - 2), frame(0, frames - 1);
    const int id = inner(rng);
    std::vector<int> gone;
    for (int k = 0; k < 1 + seed % 3; ++k) gone.push_back(frame(rng));
    std::sort(gone.begin(), gone.end());
    gone.erase(std::unique(gone.begin(), gone.end()), gone.end());
    for (int f : gone) remove_slice(seq, f, id);
    const std::vector<ContourFill> fills = fill_contour_gaps(seq);
    ASSERT_EQ(fills.size(), gone.size()) << "seed " << seed;
    for (int f : gone) {
      const Contour* c = find(seq, f, id);
      ASSERT_NE(c, nullptr) << "seed " << seed << " frame " << f;
      // The blend is linear in time: on a cycle of 10 frames whose radii swing 5 mm, the chord misses the
      // motion by up to 0.6 mm where two frames in a row are left out.
      EXPECT_LT(two_way(*c, *find(truth, f, id)), 0.75) << "seed " << seed << " frame " << f;
      EXPECT_EQ(c->label, "lv-endo");
      EXPECT_NEAR(c->points.front().z, 10.0 * id, 1e-9);
    }
    for (const Frame& fr : seq.frames)  // still sorted by offset
      for (std::size_t k = 1; k < fr.slices.size(); ++k) EXPECT_LT(fr.slices[k - 1].offset, fr.slices[k].offset);
  }
}

TEST(ContourGaps, TheStructuresEndIsLeftAsItIs) {
  std::mt19937 rng(5);
  Sequence seq = cycle(rng, 5, 12);
  for (int f = 4; f < 8; ++f) remove_slice(seq, f, 4);  // the top slice leaves the structure in mid-cycle
  EXPECT_TRUE(fill_contour_gaps(seq).empty());
  EXPECT_EQ(find(seq, 5, 4), nullptr);
}

TEST(ContourGaps, SlicesWithTwoContoursAreNotBlended) {
  std::mt19937 rng(9);
  Sequence seq = cycle(rng, 5, 8);
  for (Frame& fr : seq.frames) {  // slice 2 a ring: an inner contour too
    Contour inner = fr.slices[2].contours.front();
    for (Vec3& p : inner.points) p = {0.3 * p.x, 0.3 * p.y, p.z};
    fr.slices[2].contours.push_back(inner);
  }
  remove_slice(seq, 3, 2);
  EXPECT_TRUE(fill_contour_gaps(seq).empty());
}

TEST(ContourGaps, OneFrameOrNoGapChangesNothing) {
  std::mt19937 rng(2);
  Sequence one = cycle(rng, 5, 1);
  EXPECT_TRUE(fill_contour_gaps(one).empty());
  Sequence full = cycle(rng, 5, 6);
  EXPECT_TRUE(fill_contour_gaps(full).empty());
}

}  // namespace
}  // namespace c4d
