// Interpolation between frames: exact at key frames, linear midpoints, periodic C1 Catmull-Rom.
#include "contour4d/temporal/interpolate.h"

#include <gtest/gtest.h>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

MeshSequence circle_motion(std::size_t n) {
  // One vertex moving on a circle over a period of n * 100 ms: a smooth periodic curve.
  MeshSequence s;
  s.triangles = {{0, 1, 2}};
  for (std::size_t f = 0; f < n; ++f) {
    const double a = 2.0 * 3.14159265358979 * static_cast<double>(f) / static_cast<double>(n);
    s.positions.push_back({{10 * std::cos(a), 10 * std::sin(a), 0}, {0, 0, 1}, {1, 0, 1}});
    s.times_ms.push_back(100.0 * static_cast<double>(f));
  }
  return s;
}

TEST(Interpolate, KeyFramesExact) {
  const MeshSequence s = circle_motion(10);
  for (auto mode : {TimeInterpolation::Step, TimeInterpolation::Linear, TimeInterpolation::CatmullRomPeriodic})
    for (std::size_t f = 0; f < 10; ++f) {
      const auto p = interpolate_positions(s, s.times_ms[f], mode);
      EXPECT_NEAR(distance(p[0], s.positions[f][0]), 0.0, 1e-12);
    }
}

TEST(Interpolate, LinearMidpoint) {
  const MeshSequence s = circle_motion(10);
  const auto p = interpolate_positions(s, 150.0, TimeInterpolation::Linear);
  EXPECT_NEAR(distance(p[0], 0.5 * (s.positions[1][0] + s.positions[2][0])), 0.0, 1e-12);
  // Clamped outside the frames.
  EXPECT_NEAR(distance(interpolate_positions(s, 5000.0, TimeInterpolation::Linear)[0], s.positions[9][0]), 0.0, 1e-12);
}

TEST(Interpolate, CatmullRomFollowsCycleBetterAndWraps) {
  const MeshSequence s = circle_motion(12);
  double err_lin = 0, err_cr = 0;
  for (double t = 0; t < 1200.0; t += 7.0) {
    const double a = 2.0 * 3.14159265358979 * t / 1200.0;
    const Vec3 truth{10 * std::cos(a), 10 * std::sin(a), 0};
    err_cr = std::max(err_cr, distance(interpolate_positions(s, t, TimeInterpolation::CatmullRomPeriodic)[0], truth));
    if (t <= 1100.0)
      err_lin = std::max(err_lin, distance(interpolate_positions(s, t, TimeInterpolation::Linear)[0], truth));
  }
  EXPECT_LT(err_cr, err_lin);
  EXPECT_LT(err_cr, 0.05);
  // Periodic: t and t + period give the same positions.
  const auto a = interpolate_positions(s, 1150.0, TimeInterpolation::CatmullRomPeriodic);
  const auto b = interpolate_positions(s, 1150.0 + 1200.0, TimeInterpolation::CatmullRomPeriodic);
  EXPECT_NEAR(distance(a[0], b[0]), 0.0, 1e-9);
}

TEST(Interpolate, CatmullRomWeightsPartitionOfUnity) {
  for (double u = 0; u <= 1.0; u += 0.125) {
    double w[4];
    catmull_rom_weights(u, w);
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 1e-14);
  }
}

TEST(Interpolate, Resample) {
  const MeshSequence s = circle_motion(10);
  const MeshSequence r = resample_sequence(s, 40, TimeInterpolation::CatmullRomPeriodic);
  ASSERT_EQ(r.positions.size(), 40u);
  EXPECT_EQ(r.triangles, s.triangles);
  EXPECT_NEAR(r.times_ms[4], 100.0, 1e-9);
  EXPECT_NEAR(distance(r.positions[4][0], s.positions[1][0]), 0.0, 1e-9);
  const MeshSequence l = resample_sequence(s, 19, TimeInterpolation::Linear);
  EXPECT_NEAR(l.times_ms.back(), 900.0, 1e-9);
  EXPECT_THROW(resample_sequence(s, 0, TimeInterpolation::Linear), InvalidInput);
  MeshSequence bad = s;
  bad.times_ms[3] = bad.times_ms[2];
  EXPECT_THROW(interpolate_positions(bad, 10.0, TimeInterpolation::Linear), InvalidInput);
}

}  // namespace
}  // namespace c4d
