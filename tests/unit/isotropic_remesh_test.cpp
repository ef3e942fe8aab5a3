// Fast isotropic remeshing (isotropic_remesh.h): properties on meshes built in code, and the
// one-frame surface of the phantoms with SurfaceOptions::remesher = Fast against CGAL's.
#include "contour4d/surface/isotropic_remesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contour4d/phantoms/phantom.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/surface/reconstruct.h"

namespace {

using c4d::Triangle;
using c4d::TriangleMesh;
using c4d::Vec3;

// A UV sphere of radius r (coarse, with long edges near the equator and slivers at the poles).
TriangleMesh uv_sphere(double r, int rings, int segments) {
  TriangleMesh m;
  m.positions.push_back({0, 0, r});
  for (int i = 1; i < rings; ++i) {
    const double th = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * std::numbers::pi * j / segments;
      m.positions.push_back({r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
    }
  }
  m.positions.push_back({0, 0, -r});
  const auto south = static_cast<std::uint32_t>(m.positions.size() - 1);
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * segments + (j % segments)); };
  for (int j = 0; j < segments; ++j) m.triangles.push_back({0, at(1, j), at(1, j + 1)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.triangles.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
  return m;
}

double mean_edge(const TriangleMesh& m) {
  double sum = 0;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) sum += c4d::distance(m.positions[t[k]], m.positions[t[(k + 1) % 3]]);
  return sum / (3.0 * static_cast<double>(m.triangles.size()));
}

TEST(IsotropicRemesh, SphereBecomesIsotropicClosedAndStaysOnTheInput) {
  TriangleMesh m = uv_sphere(10.0, 12, 24);
  const TriangleMesh input = m;
  std::vector<std::array<std::uint32_t, 2>> constrained;
  std::vector<char> fixed;
  ASSERT_TRUE(c4d::remesh_isotropic_fast(m, constrained, fixed, 1.0, 5));
  const c4d::TopologyReport c = c4d::check_topology(m);
  EXPECT_TRUE(c.closed_manifold());
  EXPECT_EQ(c.self_intersections, 0u);
  EXPECT_EQ(c.euler, 2);
  EXPECT_NEAR(mean_edge(m), 1.0, 0.15);
  // Every vertex lies on the input polyhedron (inside the sphere by at most its chordal error).
  const double chord = 10.0 * (1 - std::cos(std::numbers::pi / 12));
  for (const Vec3& p : m.positions) {
    EXPECT_LE(c4d::norm(p), 10.0 + 1e-9);
    EXPECT_GE(c4d::norm(p), 10.0 - chord - 1e-9);
  }
  EXPECT_GT(m.positions.size(), 5 * input.positions.size());
}

TEST(IsotropicRemesh, ConstrainedEdgesAndFixedVerticesStay) {
  TriangleMesh m = uv_sphere(10.0, 12, 24);
  // The equator (ring 6) as a constrained loop, and the north pole fixed.
  std::vector<std::array<std::uint32_t, 2>> constrained;
  const std::uint32_t first = 1 + 5 * 24;
  for (std::uint32_t j = 0; j < 24; ++j) constrained.push_back({first + j, first + (j + 1) % 24});
  std::vector<char> fixed(m.positions.size(), 0);
  fixed[0] = 1;
  const std::vector<Vec3> before = m.positions;
  // Equator edges are 2.6 mm: longer than 4/3 of 1.5, so only the constraint keeps them whole.
  ASSERT_TRUE(c4d::remesh_isotropic_fast(m, constrained, fixed, 1.5, 4));
  EXPECT_EQ(constrained.size(), 24u);
  for (const auto& e : constrained) {
    EXPECT_TRUE(fixed[e[0]] && fixed[e[1]]);
    EXPECT_NEAR(std::abs(m.positions[e[0]].z), 0.0, 1e-12);
    EXPECT_NEAR(c4d::distance(m.positions[e[0]], m.positions[e[1]]), c4d::distance(before[first], before[first + 1]),
                1e-9);
  }
  // Old vertices keep their order: the pole is still vertex 0, unmoved.
  EXPECT_EQ(m.positions[0].x, before[0].x);
  EXPECT_EQ(m.positions[0].z, before[0].z);
  EXPECT_TRUE(c4d::check_topology(m).closed_manifold());
}

TEST(IsotropicRemesh, DeterministicAndRejectsNonManifold) {
  TriangleMesh a = uv_sphere(8.0, 10, 20), b = a;
  std::vector<std::array<std::uint32_t, 2>> ca, cb;
  std::vector<char> fa, fb;
  ASSERT_TRUE(c4d::remesh_isotropic_fast(a, ca, fa, 0.8, 3));
  ASSERT_TRUE(c4d::remesh_isotropic_fast(b, cb, fb, 0.8, 3));
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t v = 0; v < a.positions.size(); ++v) EXPECT_TRUE(a.positions[v] == b.positions[v]);
  EXPECT_EQ(a.triangles, b.triangles);
  // Two tetrahedra sharing one vertex: not a manifold; left untouched.
  TriangleMesh bow;
  bow.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  bow.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  bow.triangles.push_back({0, 2, 1});  // a duplicated directed edge as well
  const TriangleMesh copy = bow;
  std::vector<std::array<std::uint32_t, 2>> cc;
  std::vector<char> fc;
  EXPECT_FALSE(c4d::remesh_isotropic_fast(bow, cc, fc, 0.3, 2));
  EXPECT_EQ(bow.triangles, copy.triangles);
}

// The one-frame surface by remeshed bands (SurfaceOptions::rows = false) with the fast engine has the same
// topology as with CGAL's, and about the same volume and vertex count.
TEST(IsotropicRemesh, PhantomSurfacesMatchCgalEngine) {
  for (const char* name : {"ellipsoid", "torus", "left-heart-ed"}) {
    SCOPED_TRACE(name);
    const c4d::Phantom ph = c4d::make_phantom(name, {});
    c4d::SurfaceOptions fast, cgal;
    fast.rows = cgal.rows = false;
    fast.remesher = c4d::RemeshEngine::Fast;
    cgal.remesher = c4d::RemeshEngine::Cgal;
    c4d::SurfaceReport rf, rc;
    const TriangleMesh mf = c4d::reconstruct_frame(ph.contours, 0, fast, &rf);
    const TriangleMesh mc = c4d::reconstruct_frame(ph.contours, 0, cgal, &rc);
    EXPECT_TRUE(rf.closed);
    EXPECT_FALSE(rf.self_intersects);
    EXPECT_EQ(rf.components, 1);
    EXPECT_EQ(rf.euler, rc.euler);
    EXPECT_NEAR(rf.volume / rc.volume, 1.0, 0.005);
    EXPECT_NEAR(static_cast<double>(mf.positions.size()) / static_cast<double>(mc.positions.size()), 1.0, 0.1);
  }
}

}  // namespace
