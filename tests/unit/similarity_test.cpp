// Similarity index (Lim et al. 2014, eqs. 5–6): analytic cases and symmetries.
#include "contour4d/connect/similarity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using c4d::Vec2;

std::vector<Vec2> circle(double cx, double cy, double r, int n, double phase = 0.0) {
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double a = phase + 2.0 * M_PI * i / n;
    p.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
  }
  return p;
}

TEST(Similarity, IdenticalContoursScoreOne) {
  const auto a = circle(0, 0, 10, 64);
  EXPECT_NEAR(c4d::contour_similarity(a, a), 1.0, 1e-12);
}

TEST(Similarity, DisjointContoursScoreZero) {
  EXPECT_EQ(c4d::contour_similarity(circle(0, 0, 5, 32), circle(20, 0, 5, 32)), 0.0);
}

TEST(Similarity, NestedSmallContourScoresOne) {
  const auto big = circle(0, 0, 10, 64), small = circle(1, 0, 3, 32);
  EXPECT_NEAR(c4d::perimeter_inside(small, big), 1.0, 1e-12);
  EXPECT_NEAR(c4d::perimeter_inside(big, small), 0.0, 1e-12);
  EXPECT_NEAR(c4d::contour_similarity(big, small), 1.0, 1e-12);
}

TEST(Similarity, HalfPlaneOverlapMatchesGeometry) {
  // Two unit-ish circles whose centres are one radius apart: a third of each perimeter (120°) lies in the other.
  const auto a = circle(0, 0, 10, 720), b = circle(10, 0, 10, 720, 0.001);
  EXPECT_NEAR(c4d::perimeter_inside(a, b), 1.0 / 3.0, 2e-3);
  EXPECT_NEAR(c4d::contour_similarity(a, b), 1.0 / 3.0, 2e-3);
}

TEST(Similarity, SymmetricAndIndependentOfOrientationAndStart) {
  const auto a = circle(0, 0, 10, 50), b = circle(6, 2, 7, 37);
  auto r = a;
  std::reverse(r.begin(), r.end());
  std::rotate(r.begin(), r.begin() + 13, r.end());
  const double s = c4d::contour_similarity(a, b);
  EXPECT_NEAR(s, c4d::contour_similarity(b, a), 1e-12);
  EXPECT_NEAR(s, c4d::contour_similarity(r, b), 1e-12);
  EXPECT_GT(s, 0.0);
  EXPECT_LT(s, 1.0);
}

TEST(Similarity, SliceSimilaritySumsBestMatches) {
  const std::vector<std::vector<Vec2>> a{circle(0, 0, 5, 32), circle(20, 0, 5, 32)};
  const std::vector<std::vector<Vec2>> b{circle(0, 0, 5, 32)};
  EXPECT_NEAR(c4d::slice_similarity(a, b), 1.0, 1e-12);
  EXPECT_NEAR(c4d::slice_similarity(b, a), 1.0, 1e-12);
}

}  // namespace
