// Traced contours smoothed within a tolerance (contour_smoothing.h), on families of jagged shapes with random
// seeds: every point within the tolerance both ways, the area kept, the jags gone, the result independent of
// the start point and the orientation, exact contours (tolerance 0) untouched, points kept in their plane.
#include "contour4d/core/contour_smoothing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "contour4d/core/contour.h"

namespace c4d {
namespace {

// An ellipse-like blob (radii a, b, a few low harmonics) traced on a pixel grid of size `pixel`: every point
// rounded to the nearest pixel centre, as hand tracing on an image gives.
std::vector<Vec2> traced_blob(std::mt19937& rng, double pixel, int n) {
  std::uniform_real_distribution<double> radius(12.0, 30.0), ratio(0.6, 1.0), wobble(-0.08, 0.08), phase(0.0, 6.28);
  const double a = radius(rng), b = a * ratio(rng), w2 = wobble(rng), w3 = wobble(rng), p2 = phase(rng),
               p3 = phase(rng);
  std::vector<Vec2> out;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    const double s = 1.0 + w2 * std::cos(2 * t + p2) + w3 * std::cos(3 * t + p3);
    const Vec2 p{a * s * std::cos(t), b * s * std::sin(t)};
    out.push_back({pixel * std::round(p.x / pixel), pixel * std::round(p.y / pixel)});
  }
  out.erase(std::unique(out.begin(), out.end(), [](Vec2 x, Vec2 y) { return x.x == y.x && x.y == y.y; }), out.end());
  return out;
}

// Sum of |turning angle change| between consecutive vertices: large for a staircase, small for a smooth curve.
double roughness(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  std::vector<double> turn(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = p[i] - p[(i + n - 1) % n], b = p[(i + 1) % n] - p[i];
    turn[i] = std::atan2(a.x * b.y - a.y * b.x, a.x * b.x + a.y * b.y);
  }
  double r = 0.0;
  for (std::size_t i = 0; i < n; ++i) r += std::abs(turn[(i + 1) % n] - turn[i]);
  return r;
}

double two_way(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double d = 0.0;
  for (const Vec2& p : a) d = std::max(d, polyline_distance(p, b));
  for (const Vec2& p : b) d = std::max(d, polyline_distance(p, a));
  return d;
}

TEST(ContourSmoothing, TracedBlobsAreSmoothedWithinTheToleranceWithTheirArea) {
  for (int seed = 1; seed <= 12; ++seed) {
    std::mt19937 rng(seed);
    const double pixel = seed % 2 ? 1.367 : 0.7;
    const std::vector<Vec2> traced = traced_blob(rng, pixel, 160 + 20 * seed);
    const double tol = 0.5 * pixel;
    double stiffness = 0.0;
    const std::vector<Vec2> s = smooth_polygon(traced, tol, &stiffness);
    SCOPED_TRACE("seed " + std::to_string(seed));
    ASSERT_EQ(s.size(), traced.size());
    EXPECT_GT(stiffness, 0.0);
    EXPECT_LE(two_way(traced, s), tol * (1 + 1e-9));
    EXPECT_NEAR(signed_area(s) / signed_area(traced), 1.0, 0.002);
    EXPECT_LT(roughness(s), 0.35 * roughness(traced));
    EXPECT_FALSE(is_self_intersecting(s));
  }
}

TEST(ContourSmoothing, IndependentOfStartPointAndOrientation) {
  std::mt19937 rng(7);
  const std::vector<Vec2> traced = traced_blob(rng, 1.0, 200);
  const std::vector<Vec2> s = smooth_polygon(traced, 0.5);
  std::vector<Vec2> rotated(traced.begin() + 37, traced.end());
  rotated.insert(rotated.end(), traced.begin(), traced.begin() + 37);
  const std::vector<Vec2> r = smooth_polygon(rotated, 0.5);
  for (std::size_t i = 0; i < traced.size(); ++i) EXPECT_LT(norm(r[i] - s[(i + 37) % s.size()]), 1e-9);
  std::vector<Vec2> reversed(traced.rbegin(), traced.rend());
  const std::vector<Vec2> v = smooth_polygon(reversed, 0.5);
  for (std::size_t i = 0; i < traced.size(); ++i) EXPECT_LT(norm(v[i] - s[traced.size() - 1 - i]), 1e-9);
}

TEST(ContourSmoothing, ExactContoursAndTinyPolygonsAreLeftAsTheyAre) {
  std::mt19937 rng(3);
  const std::vector<Vec2> traced = traced_blob(rng, 1.0, 120);
  EXPECT_EQ(smooth_polygon(traced, 0.0), traced);
  const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(smooth_polygon(square, 0.5), square);
}

// A smooth contour moves by far less than the tolerance: the smoothing removes jags, not shape.
TEST(ContourSmoothing, SmoothContoursBarelyMove) {
  std::vector<Vec2> circle;
  for (int k = 0; k < 200; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 200;
    circle.push_back({20.0 * std::cos(t), 14.0 * std::sin(t)});
  }
  const std::vector<Vec2> s = smooth_polygon(circle, 0.5);
  EXPECT_LT(two_way(circle, s), 0.5);
  EXPECT_NEAR(signed_area(s), signed_area(circle), 1e-3 * signed_area(circle));
}

TEST(ContourSmoothing, SequenceContoursStayInTheirPlanesAndAreListed) {
  Sequence seq;
  const Vec3 n = normalized(Vec3{0.2, -0.1, 1.0});
  seq.normal = n;
  seq.u = normalized(cross(Vec3{0, 1, 0}, n));
  seq.v = cross(n, seq.u);
  std::mt19937 rng(5);
  for (int f = 0; f < 2; ++f) {
    Frame fr;
    for (int s = 0; s < 3; ++s) {
      Slice sl;
      sl.id = s;
      sl.offset = 8.0 * s;
      Contour c;
      for (const Vec2& p : traced_blob(rng, 1.2, 150)) c.points.push_back(p.x * seq.u + p.y * seq.v + sl.offset * n);
      sl.contours.push_back(c);
      fr.slices.push_back(sl);
    }
    seq.frames.push_back(fr);
  }
  const Sequence before = seq;
  const std::vector<ContourSmoothing> done = smooth_contours(seq, 0.6);
  ASSERT_EQ(done.size(), 6u);
  for (const ContourSmoothing& c : done) {
    EXPECT_LE(c.moved_max_mm, 0.6 + 1e-9);
    EXPECT_GT(c.moved_mean_mm, 0.0);
    EXPECT_GT(c.stiffness, 0.0);
  }
  for (std::size_t f = 0; f < seq.frames.size(); ++f)
    for (std::size_t s = 0; s < 3; ++s) {
      const auto& a = before.frames[f].slices[s].contours[0].points;
      const auto& b = seq.frames[f].slices[s].contours[0].points;
      for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(dot(b[i], n), dot(a[i], n), 1e-9);
    }
}

}  // namespace
}  // namespace c4d
