// Properties of the RBF deformation and contour matching (Lim et al., "4D Morphing").
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "contour4d/core/errors.h"
#include "contour4d/motion/contour_matching.h"
#include "contour4d/motion/corner_snap.h"
#include "contour4d/motion/rbf.h"

namespace c4d {
namespace {

std::vector<Vec2> ellipse(double a, double b, Vec2 c, int n, double phase = 0) {
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double t = phase + 2 * std::numbers::pi * i / n;
    p.push_back({c.x + a * std::cos(t), c.y + b * std::sin(t)});
  }
  return p;
}

double distance_to_polygon(Vec2 q, const std::vector<Vec2>& poly) {
  double best = 1e300;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()], ab = b - a;
    const double t = std::clamp(dot(q - a, ab) / dot(ab, ab), 0.0, 1.0);
    best = std::min(best, norm(q - (a + t * ab)));
  }
  return best;
}

std::vector<Vec3> cloud() {
  std::vector<Vec3> p;
  for (int i = 0; i < 30; ++i) p.push_back({10 * std::cos(i * 1.3), 10 * std::sin(i * 0.7), 5.0 * (i % 7) - 15});
  return p;
}

TEST(Rbf, InterpolatesSourcesExactly) {
  const auto src = cloud();
  std::vector<Vec3> dst = src;
  for (std::size_t i = 0; i < dst.size(); ++i) dst[i] += Vec3{std::sin(i * 1.0), std::cos(i * 2.0), 0.5};
  const RbfDeformer f(src, dst);
  for (std::size_t i = 0; i < src.size(); ++i) EXPECT_NEAR(distance(f.apply(src[i]), dst[i]), 0, 1e-8);
}

TEST(Rbf, AffineTermReproducesRigidMotionEverywhere) {
  const auto src = cloud();
  const double c = std::cos(0.4), s = std::sin(0.4);
  auto rigid = [&](Vec3 p) { return Vec3{c * p.x - s * p.y + 3, s * p.x + c * p.y - 2, p.z + 7}; };
  std::vector<Vec3> dst;
  for (const Vec3& p : src) dst.push_back(rigid(p));
  const RbfDeformer f(src, dst);
  for (Vec3 q : {Vec3{1, 2, 3}, Vec3{-20, 5, 40}, Vec3{0, 0, 0}}) EXPECT_NEAR(distance(f.apply(q), rigid(q)), 0, 1e-7);
}

// RbfDeformer::apply(points) sums several points' multiquadrics per SIMD instruction (four with AVX, two
// with SSE2, the last few one by one): each point's result is apply(p)'s, bit for bit, with and without
// the affine term, whatever the count.
TEST(Rbf, ManyPointsGiveEachPointsOwnResultBitForBit) {
  const auto src = cloud();
  std::vector<Vec3> dst = src;
  for (std::size_t i = 0; i < dst.size(); ++i) dst[i] += Vec3{std::sin(i * 1.0), std::cos(i * 2.0), 0.5};
  for (bool affine : {true, false}) {
    RbfOptions o;
    o.affine = affine;
    const RbfDeformer f(src, dst, o);
    for (std::size_t count : {1u, 3u, 4u, 7u, 53u}) {
      std::vector<Vec3> pts;
      for (std::size_t i = 0; i < count; ++i)
        pts.push_back({7 * std::sin(i * 0.9), 11 * std::cos(i * 0.4), 0.3 * i - 6});
      const std::vector<Vec3> in = pts;
      f.apply(pts);
      for (std::size_t i = 0; i < count; ++i) {
        const Vec3 one = f.apply(in[i]);
        EXPECT_TRUE(one.x == pts[i].x && one.y == pts[i].y && one.z == pts[i].z) << "point " << i << " of " << count;
      }
    }
  }
}

TEST(Rbf, SubStepsReachTheTargets) {
  const auto src = cloud();
  std::vector<Vec3> dst = src, pts = src;
  for (Vec3& p : dst) p = p * 1.2 + Vec3{0, 0, 3};
  deform_rbf(pts, src, dst, 10);
  for (std::size_t i = 0; i < src.size(); ++i) EXPECT_NEAR(distance(pts[i], dst[i]), 0, 1e-6);
}

TEST(Rbf, CoplanarSourcesWithAffineTermAreReported) {
  std::vector<Vec3> flat;
  for (int i = 0; i < 8; ++i) flat.push_back({std::cos(i * 0.8), std::sin(i * 0.8), 0});
  EXPECT_THROW(RbfDeformer(flat, flat), SolverError);
}

TEST(ContourMatching, CrossingContoursUseBreakPointsAndLandOnTarget) {
  const auto src = ellipse(10, 6, {0, 0}, 120);
  const auto dst = ellipse(7, 9, {1, 0.5}, 90);
  const ContourMatch m = match_contour(src, dst);
  EXPECT_EQ(m.method, MatchMethod::BreakPoints);
  EXPECT_EQ(m.break_points, 4);
  ASSERT_EQ(m.targets.size(), src.size());
  for (Vec2 q : m.targets) EXPECT_LT(distance_to_polygon(q, dst), 1e-9);
}

TEST(ContourMatching, NestedContoursAlignAndKeepCyclicOrder) {
  const auto src = ellipse(10, 10, {0, 0}, 100);
  const auto dst = ellipse(5, 5, {0.5, 0}, 64, 0.3);
  const ContourMatch m = match_contour(src, dst);
  EXPECT_EQ(m.method, MatchMethod::Aligned);
  // Concentric circles: each point moves radially inwards, so the angle is kept.
  for (std::size_t i = 0; i < src.size(); ++i) {
    const double a0 = std::atan2(src[i].y, src[i].x), a1 = std::atan2(m.targets[i].y, m.targets[i].x - 0.5);
    EXPECT_NEAR(std::remainder(a1 - a0, 2 * std::numbers::pi), 0, 0.05);
    EXPECT_LT(distance_to_polygon(m.targets[i], dst), 1e-9);
  }
}

TEST(ContourMatching, TargetOrientationAndStartPointDoNotMatter) {
  const auto src = ellipse(10, 6, {0, 0}, 80);
  auto dst = ellipse(7, 9, {1, 0.5}, 90);
  const ContourMatch a = match_contour(src, dst);
  std::reverse(dst.begin(), dst.end());
  std::rotate(dst.begin(), dst.begin() + 17, dst.end());
  const ContourMatch b = match_contour(src, dst);
  for (std::size_t i = 0; i < src.size(); ++i) EXPECT_NEAR(norm(a.targets[i] - b.targets[i]), 0, 1e-9);
}

// A coarse, jagged target (fewer points than the source, with corners between consecutive targets):
// the points between two targets stay on the target polygon, in order, where the chord would cut the
// corners; both ends are the targets themselves. Both matching methods.
TEST(ContourMatching, PointsBetweenTargetsFollowTheTargetPolygon) {
  std::vector<Vec2> jagged = ellipse(9, 8, {0.5, 0}, 24);
  for (std::size_t i = 0; i < jagged.size(); i += 2) jagged[i] = 1.04 * jagged[i];  // zig-zag of about 0.35 mm
  for (const auto& src : {ellipse(10, 6, {0, 0}, 120), ellipse(12, 12, {0, 0}, 120)}) {
    const ContourMatch m = match_contour(src, jagged);
    ASSERT_EQ(m.arc.size(), src.size());
    double chord_worst = 0, between_worst = 0;
    for (std::size_t i = 0; i < src.size(); ++i) {
      EXPECT_LT(norm(target_between(m, i, 0.0) - m.targets[i]), 1e-9);
      EXPECT_LT(norm(target_between(m, i, 1.0) - m.targets[(i + 1) % src.size()]), 1e-9);
      for (double f : {0.25, 0.5, 0.75}) {
        const Vec2 chord = (1 - f) * m.targets[i] + f * m.targets[(i + 1) % src.size()];
        chord_worst = std::max(chord_worst, distance_to_polygon(chord, jagged));
        between_worst = std::max(between_worst, distance_to_polygon(target_between(m, i, f), jagged));
      }
    }
    EXPECT_LT(between_worst, 1e-9);
    EXPECT_GT(chord_worst, 0.01);  // the case the function is for
  }
}

// A 10 mm square in z = 0 with a point in the middle of each side: four 90° corners, no other turn.
std::vector<Vec3> square_line() {
  return {{0, 0, 0}, {5, 0, 0}, {10, 0, 0}, {10, 5, 0}, {10, 10, 0}, {5, 10, 0}, {0, 10, 0}, {0, 5, 0}};
}

// A retry's options: any vertex near a corner is a candidate, `tries` of them.
CornerSnapOptions retry_options(std::size_t tries) {
  CornerSnapOptions o;
  o.any_vertex = true;
  o.tries = tries;
  return o;
}

TEST(CornerSnap, RetryTakesTheNearestVertexOffTheContourOntoEachCorner) {
  const std::vector<std::vector<Vec3>> lines{square_line()};
  // Per corner: a vertex 0.5 mm off it (above the plane) and one 1.2 mm off; vertex 8 on the contour, mid-side.
  const std::vector<Vec3> corners{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  std::vector<Vec3> x;
  for (const Vec3& c : corners) {
    x.push_back(c + Vec3{0.3, 0.3, 0.3});
    x.push_back(c + Vec3{0.0, 0.0, 1.2});
  }
  x.push_back({5, 0, 0});
  const std::vector<std::vector<std::uint32_t>> on_line{{8}};
  auto always = [](std::uint32_t, Vec3) { return true; };
  CornerSnapOptions o = retry_options(1);
  std::vector<Vec3> y = x;
  std::vector<char> fixed(x.size(), 0);
  EXPECT_EQ(snap_corners(y, lines, on_line, fixed, always, o), 4u);
  for (std::size_t c = 0; c < 4; ++c) {
    EXPECT_EQ(y[2 * c], corners[c]);  // exactly on the corner
    EXPECT_EQ(fixed[2 * c], 1);
    EXPECT_EQ(y[2 * c + 1], x[2 * c + 1]);
    EXPECT_EQ(fixed[2 * c + 1], 0);
  }
  EXPECT_EQ(y[8], x[8]);

  // A first try takes only vertices on the contour: the one on it is 5 mm from every corner.
  o.any_vertex = false;
  y = x;
  std::fill(fixed.begin(), fixed.end(), 0);
  EXPECT_EQ(snap_corners(y, lines, on_line, fixed, always, o), 0u);
  EXPECT_EQ(y, x);

  // A contour with no vertex on it is left alone, whatever the candidates.
  o.any_vertex = true;
  EXPECT_EQ(snap_corners(y, lines, {{}}, fixed, always, o), 0u);
  EXPECT_EQ(y, x);
}

TEST(CornerSnap, RefusedOrFixedCandidatesPassToTheNextWithinTries) {
  const std::vector<std::vector<Vec3>> lines{square_line()};
  std::vector<Vec3> x{{0.3, 0.3, 0.3}, {0.0, 0.0, 1.2}, {5, 0, 0}};
  const std::vector<std::vector<std::uint32_t>> on_line{{2}};
  auto not_nearest = [](std::uint32_t v, Vec3) { return v != 0; };
  CornerSnapOptions o = retry_options(1);
  std::vector<Vec3> y = x;
  std::vector<char> fixed(x.size(), 0);
  EXPECT_EQ(snap_corners(y, lines, on_line, fixed, not_nearest, o), 0u);
  o.tries = 2;
  EXPECT_EQ(snap_corners(y, lines, on_line, fixed, not_nearest, o), 1u);
  EXPECT_EQ(y[1], (Vec3{0, 0, 0}));
  EXPECT_EQ(y[0], x[0]);
  // A fixed vertex is passed over too.
  y = x;
  std::fill(fixed.begin(), fixed.end(), 0);
  fixed[0] = 1;
  EXPECT_EQ(snap_corners(
                y, lines, on_line, fixed, [](std::uint32_t, Vec3) { return true; }, o),
            1u);
  EXPECT_EQ(y[0], x[0]);
  EXPECT_EQ(y[1], (Vec3{0, 0, 0}));
}

TEST(CornerSnap, GentleTurnsAreNoCorners) {
  // A 36-gon turns by 10° at each point, under the 30° of a corner.
  std::vector<Vec3> circle;
  for (int i = 0; i < 36; ++i)
    circle.push_back({10 * std::cos(i * std::numbers::pi / 18), 10 * std::sin(i * std::numbers::pi / 18), 0});
  std::vector<Vec3> x{{10.2, 0.1, 0.2}, circle[9]};
  std::vector<char> fixed(x.size(), 0);
  const CornerSnapOptions o = retry_options(3);
  std::vector<Vec3> y = x;
  EXPECT_EQ(snap_corners(
                y, {circle}, {{1}}, fixed, [](std::uint32_t, Vec3) { return true; }, o),
            0u);
  EXPECT_EQ(y, x);
}

}  // namespace
}  // namespace c4d
