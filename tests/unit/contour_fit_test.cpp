// Properties of the last fit of a morphed frame onto its contours (contour_fit.h; Lim et al. 2014,
// "Mesh Conformity"): it brings the surface onto contours that lie off it, leaves a surface that
// already passes through its contours alone, keeps fixed vertices, and commutes with rigid motion.
#include <cmath>
#include <cstdint>
#include <numbers>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "contour4d/metrics/quality.h"
#include "contour4d/motion/contour_fit.h"
#include "contour4d/motion/section.h"
#include "contour4d/metrics/surface_walk.h"
#include "metrics_fixtures.h"

namespace c4d {
namespace {

// A sphere of radius 20 mm (edges about 2 mm) and a circle of radius r in the plane z = h.
TriangleMesh sphere() { return test::icosphere(20.0, 4); }

std::vector<Vec3> circle(double r, double h, int n = 120) {
  std::vector<Vec3> c;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    c.push_back({r * std::cos(t), r * std::sin(t), h});
  }
  return c;
}

TEST(ContourFit, BringsTheSurfaceOntoAContourOffIt) {
  TriangleMesh m = sphere();
  // The exact sphere's section at z = 6 has radius sqrt(400 - 36) ≈ 19.08; the circle lies 0.3 mm outside.
  const std::vector<std::vector<Vec3>> contours = {circle(std::sqrt(400.0 - 36.0) + 0.3, 6.0)};
  const double before_min_angle = angle_quality(m).min_angle_deg;
  const ContourFitReport r = fit_to_contours(m.positions, m.triangles, contours, {});
  EXPECT_GT(r.max_before_mm, 0.3);
  EXPECT_LT(r.max_after_mm, 0.1);
  EXPECT_GT(r.moved, 0u);
  // A smooth, small displacement: the triangles keep their shapes.
  EXPECT_GT(angle_quality(m).min_angle_deg, before_min_angle - 5.0);
}

TEST(ContourFit, LeavesASurfaceThroughItsContoursAlone) {
  TriangleMesh m = sphere();
  Plane pl;
  pl.origin = {0, 0, 3.7};
  const std::vector<std::vector<Vec3>> contours = plane_section(m, pl);  // exactly on the mesh
  ASSERT_FALSE(contours.empty());
  const std::vector<Vec3> before = m.positions;
  const ContourFitReport r = fit_to_contours(m.positions, m.triangles, contours, {});
  EXPECT_LT(r.max_before_mm, 1e-9);
  EXPECT_EQ(r.moved, 0u);
  EXPECT_EQ(m.positions, before);
}

TEST(ContourFit, FixedVerticesStay) {
  TriangleMesh m = sphere();
  const std::vector<std::vector<Vec3>> contours = {circle(std::sqrt(400.0 - 36.0) + 0.3, 6.0)};
  std::vector<char> fixed(m.positions.size(), 0);
  for (std::size_t v = 0; v < fixed.size(); v += 2) fixed[v] = 1;
  const std::vector<Vec3> before = m.positions;
  fit_to_contours(m.positions, m.triangles, contours, fixed);
  for (std::size_t v = 0; v < fixed.size(); v += 2) EXPECT_EQ(m.positions[v], before[v]) << v;
}

TEST(ContourFit, CommutesWithRigidMotion) {
  const double c = std::cos(0.7), s = std::sin(0.7);
  auto rigid = [&](Vec3 p) { return Vec3{c * p.x - s * p.z + 12.5, p.y - 40.0, s * p.x + c * p.z + 3.25}; };
  TriangleMesh a = sphere(), b = sphere();
  std::vector<Vec3> ring = circle(std::sqrt(400.0 - 36.0) + 0.3, 6.0), moved_ring;
  for (Vec3& p : b.positions) p = rigid(p);
  for (const Vec3& p : ring) moved_ring.push_back(rigid(p));
  fit_to_contours(a.positions, a.triangles, {ring}, {});
  fit_to_contours(b.positions, b.triangles, {moved_ring}, {});
  for (std::size_t v = 0; v < a.positions.size(); ++v)
    EXPECT_NEAR(distance(rigid(a.positions[v]), b.positions[v]), 0, 1e-6) << v;
}

// The closest points of an earlier call (sample_triangles) only start the search: a warm call fits as a
// cold one does, and hands back a triangle for every sample within reach.
TEST(ContourFit, WarmStartFromEarlierClosestPointsFitsTheSame) {
  const std::vector<Vec3> samples = contour_fit_samples({circle(std::sqrt(400.0 - 36.0) + 0.3, 6.0)}, 0.2);
  TriangleMesh cold = sphere(), warm = sphere();
  // The earlier call: a measurement on the mesh a little off (as a guarded fit's rounds are).
  std::vector<Vec3> earlier = warm.positions;
  for (Vec3& p : earlier) p = p + Vec3{0.05, -0.03, 0.02};
  std::vector<std::int32_t> hints;
  ContourFitOptions measure;
  measure.iterations = 0;
  fit_to_points(earlier, warm.triangles, samples, {}, measure, &hints);
  ASSERT_EQ(hints.size(), samples.size());
  for (std::int32_t h : hints) ASSERT_GE(h, 0);
  const ContourFitReport a = fit_to_points(cold.positions, cold.triangles, samples, {});
  const ContourFitReport b = fit_to_points(warm.positions, warm.triangles, samples, {}, {}, &hints);
  EXPECT_NEAR(a.max_before_mm, b.max_before_mm, 1e-9);
  EXPECT_NEAR(a.max_after_mm, b.max_after_mm, 1e-9);
  EXPECT_EQ(a.moved, b.moved);
  for (std::size_t v = 0; v < cold.positions.size(); ++v)
    EXPECT_NEAR(distance(cold.positions[v], warm.positions[v]), 0, 1e-9) << v;
  // Hints of the wrong size are ignored (a cold search).
  std::vector<std::int32_t> stale(3, 0);
  TriangleMesh again = sphere();
  const ContourFitReport c = fit_to_points(again.positions, again.triangles, samples, {}, {}, &stale);
  EXPECT_NEAR(c.max_after_mm, a.max_after_mm, 1e-9);
  EXPECT_EQ(stale.size(), samples.size());
}

TEST(ContourFit, SearchesWithoutEarlierAnswersFindTheClosestPoints) {
  // Samples on three contours far apart, some a millimetre off the surface: each search starts from the
  // answer of the sample before it (fit_to_points), yet finds the closest point of the whole surface, and
  // the answers do not depend on the thread count.
  std::vector<Vec3> samples =
      contour_fit_samples({circle(std::sqrt(400.0 - 36.0) + 0.3, 6.0), circle(std::sqrt(400.0 - 169.0) - 1.0, -13.0),
                           circle(8.0, 19.0, 40)},
                          0.2);
  ASSERT_GT(samples.size(), 300u);  // several blocks of searches
  const TriangleMesh m = sphere();
  double truth = 0;
  for (const Vec3& s : samples) {
    double best = 1e300;
    for (const Triangle& t : m.triangles)
      best =
          std::min(best, distance(s, closest_on_triangle(s, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]])));
    truth = std::max(truth, best);
  }
  ContourFitOptions measure;
  measure.iterations = 0;
  measure.reach_mm = 10.0;  // every sample counts towards the largest distance
  std::vector<Vec3> fitted[2];
  for (int threads : {1, 2}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    std::vector<Vec3> probe = m.positions;
    EXPECT_NEAR(fit_to_points(probe, m.triangles, samples, {}, measure).max_before_mm, truth, 1e-9) << threads;
    fitted[threads - 1] = m.positions;
    fit_to_points(fitted[threads - 1], m.triangles, samples, {});
  }
  for (std::size_t v = 0; v < m.positions.size(); ++v) EXPECT_EQ(fitted[0][v], fitted[1][v]) << v;
}

}  // namespace
}  // namespace c4d
