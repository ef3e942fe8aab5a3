// Marching squares, Taubin smoothing and resampling on hand-made fields and analytic discs.
#include "contour4d/extract/marching_squares.h"

#include <gtest/gtest.h>

#include "ellipse_distance.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "contour4d/core/contour.h"

namespace c4d {
namespace {

struct Field {
  int w, h;
  std::vector<float> v;
  Field(int w_, int h_) : w(w_), h(h_), v(static_cast<std::size_t>(w_ * h_), 0.0f) {}
  void set(int x, int y, float f = 1.0f) { v[static_cast<std::size_t>(x + w * y)] = f; }
};

Field disc(int n, double cx, double cy, double r) {
  Field f(n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < r * r) f.set(x, y);
  return f;
}

double max_radial_error(const std::vector<Vec2>& c, double cx, double cy, double r) {
  double e = 0;
  for (const Vec2& p : c) e = std::max(e, std::abs(std::hypot(p.x - cx, p.y - cy) - r));
  return e;
}

double rms_radial_error(const std::vector<Vec2>& c, double cx, double cy, double r) {
  double s = 0;
  for (const Vec2& p : c) s += std::pow(std::hypot(p.x - cx, p.y - cy) - r, 2);
  return std::sqrt(s / static_cast<double>(c.size()));
}

TEST(MarchingSquares, SinglePixelIsOneCounterClockwiseDiamond) {
  Field f(3, 3);
  f.set(1, 1);
  const auto chains = marching_squares(f.v, f.w, f.h);
  ASSERT_EQ(chains.size(), 1u);
  ASSERT_EQ(chains[0].size(), 4u);
  EXPECT_NEAR(signed_area(chains[0]), 0.5, 1e-12);
  for (const Vec2& p : chains[0]) EXPECT_NEAR(std::abs(p.x - 1) + std::abs(p.y - 1), 0.5, 1e-12);
}

TEST(MarchingSquares, PixelOnTheBorderStillCloses) {
  Field f(2, 2);
  f.set(0, 0);
  const auto chains = marching_squares(f.v, f.w, f.h);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_NEAR(signed_area(chains[0]), 0.5, 1e-12);
}

TEST(MarchingSquares, RingGivesOuterBoundaryAndHoleWithOppositeOrientation) {
  Field f(9, 9);
  for (int y = 1; y <= 7; ++y)
    for (int x = 1; x <= 7; ++x)
      if (x < 3 || x > 5 || y < 3 || y > 5) f.set(x, y);
  const auto chains = marching_squares(f.v, f.w, f.h);
  ASSERT_EQ(chains.size(), 2u);
  const double a0 = signed_area(chains[0]), a1 = signed_area(chains[1]);
  EXPECT_GT(std::max(a0, a1), 0.0);
  EXPECT_LT(std::min(a0, a1), 0.0);
  // Outer: 7×7 block minus corner triangles (4 × 0.125); hole: 3×3 minus corner triangles.
  EXPECT_NEAR(std::max(a0, a1), 49 - 0.5, 1e-12);
  EXPECT_NEAR(std::min(a0, a1), -(9 - 0.5), 1e-12);
}

TEST(MarchingSquares, SaddleSeparatesDiagonalPixelsOfAMask) {
  Field f(4, 4);
  f.set(1, 1);
  f.set(2, 2);
  EXPECT_EQ(marching_squares(f.v, f.w, f.h).size(), 2u);
  // The complement: foreground diagonal neighbours are separate, so the two diagonal background
  // pixels join into one hole.
  Field g(6, 6);
  for (int y = 1; y <= 4; ++y)
    for (int x = 1; x <= 4; ++x) g.set(x, y);
  g.set(2, 2, 0.0f);
  g.set(3, 3, 0.0f);
  const auto chains = marching_squares(g.v, g.w, g.h);
  ASSERT_EQ(chains.size(), 2u);  // the outer boundary and one hole
  EXPECT_LT(std::min(signed_area(chains[0]), signed_area(chains[1])), 0.0);
}

TEST(MarchingSquares, SaddleFollowsTheCellMeanOnSmoothFields) {
  Field f(4, 4);
  f.set(1, 1, 1.0f);
  f.set(2, 2, 1.0f);
  f.set(2, 1, 0.3f);
  f.set(1, 2, 0.3f);  // mean 0.65 > 0.5: joined
  EXPECT_EQ(marching_squares(f.v, f.w, f.h).size(), 1u);
}

// A point-sampled mask fixes an edge only to ±½ pixel at the extreme rows of a disc; smoothing
// cannot recover that, but brings the typical error down to a small fraction of a pixel.
TEST(MarchingSquares, DiscWithinAFractionOfAPixelAfterSmoothing) {
  double raw_max = 0, raw_rms = 0, sm_max = 0, sm_rms = 0, g_max = 0, g_rms = 0;
  int n = 0;
  for (double r : {4.3, 6.3, 9.9, 12.7, 17.1, 25.2, 33.3})
    for (double dx : {0.0, 0.37, 0.71}) {
      const double cx = 41.1 + dx, cy = 40.81 - 0.5 * dx;
      const Field f = disc(84, cx, cy, r);
      const auto chains = marching_squares(f.v, f.w, f.h);
      ASSERT_EQ(chains.size(), 1u);
      std::vector<Vec2> c = chains[0];
      raw_max = std::max(raw_max, max_radial_error(c, cx, cy, r));
      raw_rms += rms_radial_error(c, cx, cy, r);
      smooth_closed_taubin(c, 10);
      sm_max = std::max(sm_max, max_radial_error(c, cx, cy, r));
      sm_rms += rms_radial_error(c, cx, cy, r);
      // Taubin does not shrink: the area stays within 2 % of the disc's.
      EXPECT_NEAR(signed_area(c), std::numbers::pi * r * r, 0.02 * std::numbers::pi * r * r + 1.0) << "r=" << r;
      const auto blurred = marching_squares(gaussian_blur(f.v, f.w, f.h, 1.0), f.w, f.h);
      ASSERT_EQ(blurred.size(), 1u);
      g_max = std::max(g_max, max_radial_error(blurred[0], cx, cy, r));
      g_rms += rms_radial_error(blurred[0], cx, cy, r);
      ++n;
    }
  raw_rms /= n, sm_rms /= n, g_rms /= n;
  std::printf(
      "[ figure ] disc radial error (px): raw max %.3f rms %.3f | taubin 10 max %.3f rms %.3f | gauss 1.0 max %.3f rms "
      "%.3f\n",
      raw_max, raw_rms, sm_max, sm_rms, g_max, g_rms);
  EXPECT_LE(raw_max, 0.5 + 1e-9);
  EXPECT_LT(sm_max, 0.55);
  EXPECT_LT(sm_rms, 0.2);
  EXPECT_LT(sm_rms, 0.8 * raw_rms);
  EXPECT_LT(g_max, 0.55);
  EXPECT_LT(g_rms, 0.2);
}

// Distance from p to the ellipse (centre c, semi-axes a, b, rotated by th): dense sampling refined.
double ellipse_distance(Vec2 p, Vec2 c, double a, double b, double th) {
  const Vec2 d = p - c;
  const double x = std::cos(th) * d.x + std::sin(th) * d.y, y = -std::sin(th) * d.x + std::cos(th) * d.y;
  return c4d::test::ellipse_distance_aligned(a, b, x, y, 720);
}

// The edge fit keeps every point within half a pixel of the true boundary on discs and rotated
// ellipses of many sizes and sub-pixel positions (radius of curvature >= 1.5 px), with a far smaller
// RMS than the raw staircase (max 0.5 px) and Taubin (whose curvature bias exceeds ½ px).
TEST(MarchingSquares, StaircaseFitWithinHalfAPixelOnDiscsAndEllipses) {
  double raw_max = 0, tau_max = 0, fit_max = 0, fit_rms = 0, tau_rms = 0;
  std::size_t count = 0;
  int shapes = 0;
  for (double a : {2.3, 3.1, 4.3, 6.3, 9.9, 12.7, 17.1, 25.2, 33.3, 47.5})
    for (double ratio : {1.0, 0.8, 0.55, 0.35})
      for (double th : {0.0, 0.3, 0.785})
        for (double dx : {0.0, 0.23, 0.37, 0.71, 0.93}) {
          const double b = a * ratio;
          if (b < 1.6 || b * b / a < 1.5) continue;  // tips sharper than the pixel grid resolves
          const int N = static_cast<int>(2 * a + 8);
          const Vec2 cen{N / 2.0 + dx, N / 2.0 - 0.61 * dx + 0.13};
          Field f(N, N);
          for (int y = 0; y < N; ++y)
            for (int x = 0; x < N; ++x) {
              const double ux = x - cen.x, uy = y - cen.y;
              const double X = std::cos(th) * ux + std::sin(th) * uy, Y = -std::sin(th) * ux + std::cos(th) * uy;
              if (X * X / (a * a) + Y * Y / (b * b) < 1) f.set(x, y);
            }
          const auto chains = marching_squares(f.v, f.w, f.h);
          ASSERT_EQ(chains.size(), 1u);
          const std::vector<Vec2> fit = fit_mask_staircase(chains[0], {1, 1});
          std::vector<Vec2> tau = chains[0];
          smooth_closed_taubin(tau, 10);
          ASSERT_EQ(fit.size(), chains[0].size());
          double sm = 0;
          for (std::size_t i = 0; i < fit.size(); ++i) {
            raw_max = std::max(raw_max, ellipse_distance(chains[0][i], cen, a, b, th));
            const double et = ellipse_distance(tau[i], cen, a, b, th);
            tau_max = std::max(tau_max, et);
            tau_rms += et * et;
            const double e = ellipse_distance(fit[i], cen, a, b, th);
            sm = std::max(sm, e);
            fit_rms += e * e;
            ++count;
          }
          fit_max = std::max(fit_max, sm);
          ++shapes;
        }
  fit_rms = std::sqrt(fit_rms / static_cast<double>(count));
  tau_rms = std::sqrt(tau_rms / static_cast<double>(count));
  std::printf(
      "[ figure ] %d discs/ellipses, %zu points, error (px): raw max %.3f | taubin 10 max %.3f rms %.3f | edge fit max "
      "%.3f rms %.3f\n",
      shapes, count, raw_max, tau_max, tau_rms, fit_max, fit_rms);
  EXPECT_LT(fit_max, 0.5);
  EXPECT_LT(fit_rms, 0.75 * tau_rms);
}

TEST(MarchingSquares, InvariantToTranslationByWholePixels) {
  const Field a = disc(40, 15.3, 17.6, 9.1), b = disc(40, 18.3, 21.6, 9.1);
  const auto ca = marching_squares(a.v, a.w, a.h), cb = marching_squares(b.v, b.w, b.h);
  ASSERT_EQ(ca.size(), 1u);
  ASSERT_EQ(cb.size(), 1u);
  ASSERT_EQ(ca[0].size(), cb[0].size());
  for (std::size_t i = 0; i < ca[0].size(); ++i) {
    EXPECT_DOUBLE_EQ(ca[0][i].x + 3, cb[0][i].x);
    EXPECT_DOUBLE_EQ(ca[0][i].y + 4, cb[0][i].y);
  }
}

TEST(Resample, EvenArcLengthOnASquare) {
  const std::vector<Vec2> sq = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  const auto r = resample_closed(sq, 8);
  ASSERT_EQ(r.size(), 8u);
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_NEAR(norm(r[(i + 1) % 8] - r[i]), 2.0, 1e-12);
  EXPECT_EQ(r[0], (Vec2{0, 0}));
}

TEST(GaussianBlur, PreservesMassAwayFromTheBorder) {
  Field f(21, 21);
  f.set(10, 10);
  const auto b = gaussian_blur(f.v, f.w, f.h, 1.0);
  double sum = 0;
  for (float x : b) sum += x;
  EXPECT_NEAR(sum, 1.0, 1e-5);
}

}  // namespace
}  // namespace c4d
