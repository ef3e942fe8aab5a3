// Closest points by walking (surface_walk.h): against a scan of every triangle, on meshes built in
// code, for queries near the start as the remeshing and the small-angle repair make them.
#include "contour4d/metrics/surface_walk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "contour4d/metrics/surface_projector.h"

namespace {

using c4d::Triangle;
using c4d::TriangleMesh;
using c4d::Vec3;

// A torus (major radius R, minor r) of nu × nv quads split into triangles.
TriangleMesh torus(double R, double r, int nu, int nv) {
  TriangleMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      m.positions.push_back(
          {(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

double scan_distance(const TriangleMesh& m, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Triangle& t : m.triangles)
    best = std::min(
        best, c4d::distance(p, c4d::closest_on_triangle(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]])));
  return best;
}

TEST(SurfaceWalk, ClosestOnTriangleRegions) {
  const Vec3 a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};
  auto expect = [&](Vec3 p, Vec3 want) {
    const Vec3 q = c4d::closest_on_triangle(p, a, b, c);
    EXPECT_NEAR(q.x, want.x, 1e-12);
    EXPECT_NEAR(q.y, want.y, 1e-12);
    EXPECT_NEAR(q.z, want.z, 1e-12);
  };
  expect({0.5, 0.5, 3}, {0.5, 0.5, 0});  // face
  expect({-1, -1, 1}, a);                // vertex regions
  expect({5, -1, 0}, b);
  expect({-1, 5, 0}, c);
  expect({1, -2, 0}, {1, 0, 0});  // edge regions
  expect({-2, 1, 0}, {0, 1, 0});
  expect({2, 2, -1}, {1, 1, 0});
  // A degenerate (collinear) triangle: the closest point of its edges.
  const Vec3 q = c4d::closest_on_triangle({1, 1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  EXPECT_NEAR(q.x, 1.0, 1e-12);
  EXPECT_NEAR(q.y, 0.0, 1e-12);
}

// Queries a fraction of an edge off a vertex, walked from one of its triangles, find the closest point
// of the whole surface, and the hint ends on a triangle holding it.
TEST(SurfaceWalk, NearbyQueriesFindTheClosestPointOfTheSurface) {
  const TriangleMesh m = torus(10.0, 3.0, 64, 24);
  const c4d::SurfaceWalk w = c4d::make_surface_walk(m);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> off(-0.4, 0.4);
  std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(m.positions.size() - 1));
  for (int k = 0; k < 500; ++k) {
    const std::uint32_t v = pick(rng);
    const Vec3 p = m.positions[v] + Vec3{off(rng), off(rng), off(rng)};
    std::int32_t hint = c4d::walk_start(w, v);
    ASSERT_GE(hint, 0);
    const Vec3 q = c4d::walk_closest(w, p, hint);
    EXPECT_NEAR(c4d::distance(p, q), scan_distance(m, p), 1e-12) << "query " << k;
    const Triangle& t = m.triangles[static_cast<std::size_t>(hint)];
    const Vec3 on = c4d::closest_on_triangle(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    EXPECT_EQ(c4d::distance(on, q), 0.0);
  }
}

// add_neighbour_lists: the same answers and end triangles, bit for bit, as the search around the corners,
// with two patches (the torus's halves) and queries up to an edge away from their start.
TEST(SurfaceWalk, NeighbourListsGiveTheSameWalks) {
  const TriangleMesh m = torus(10.0, 3.0, 48, 20);
  std::vector<std::int32_t> patch(m.triangles.size());
  for (std::size_t t = 0; t < patch.size(); ++t) patch[t] = t < patch.size() / 2 ? 0 : 1;
  const c4d::SurfaceWalk plain = c4d::make_surface_walk(m, patch);
  c4d::SurfaceWalk listed = plain;
  c4d::add_neighbour_lists(listed);
  ASSERT_EQ(listed.near_start.size(), m.triangles.size() + 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> off(-1.0, 1.0);
  std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(m.positions.size() - 1));
  for (int k = 0; k < 1000; ++k) {
    const std::uint32_t v = pick(rng);
    const Vec3 p = m.positions[v] + Vec3{off(rng), off(rng), off(rng)};
    std::int32_t h1 = c4d::walk_start(plain, v), h2 = h1;
    const Vec3 a = c4d::walk_closest(plain, p, h1), b = c4d::walk_closest(listed, p, h2);
    EXPECT_EQ(h1, h2) << "query " << k;
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
  }
}

// The walk stays within the patch it starts in, even where the other patch is nearer.
TEST(SurfaceWalk, StaysInItsPatch) {
  TriangleMesh m;  // two squares side by side, split into triangles: x in [0, 1] and [1, 2]
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
  m.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  const c4d::SurfaceWalk w = c4d::make_surface_walk(m, {0, 0, 1, 1});
  std::int32_t hint = 0;
  const Vec3 q = c4d::walk_closest(w, {1.8, 0.5, 0.3}, hint);
  EXPECT_LE(hint, 1);
  EXPECT_NEAR(q.x, 1.0, 1e-12);
  EXPECT_NEAR(q.y, 0.5, 1e-12);
  EXPECT_NEAR(q.z, 0.0, 1e-12);
  hint = 2;  // from the other patch: the point straight below
  const Vec3 r = c4d::walk_closest(w, {1.8, 0.5, 0.3}, hint);
  EXPECT_NEAR(r.x, 1.8, 1e-12);
  EXPECT_NEAR(r.z, 0.0, 1e-12);
  EXPECT_EQ(c4d::walk_start(w, 3), 1);
  EXPECT_EQ(c4d::walk_start(w, 2), 2);
}

// SurfaceProjector::walk answers as the tree does for queries near the last answer, carries hints
// over to a projector of the moved mesh, and falls back to the tree where a walk ends far from its
// query on the wrong sheet.
TEST(SurfaceWalk, ProjectorWalksAgreeWithTheTree) {
  TriangleMesh m = torus(10.0, 3.0, 64, 24);
  const c4d::SurfaceProjector proj(m);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> off(-0.3, 0.3);
  std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(m.positions.size() - 1));
  for (int k = 0; k < 300; ++k) {
    const Vec3 p = m.positions[pick(rng)] + Vec3{off(rng), off(rng), off(rng)};
    std::int32_t tree_hint = -1;
    const Vec3 a = proj.closest(p, nullptr, &tree_hint);
    std::int32_t walk_hint = -1;  // no hint: the tree
    const Vec3 b = proj.walk(p, nullptr, &walk_hint);
    EXPECT_EQ(c4d::distance(a, b), 0.0);
    const Vec3 q = p + Vec3{off(rng), off(rng), off(rng)};  // a nearby query, walked from there
    Vec3 normal{};
    const Vec3 c = proj.walk(q, &normal, &walk_hint);
    EXPECT_NEAR(c4d::distance(q, c), scan_distance(m, q), 1e-12) << "query " << k;
    EXPECT_NEAR(c4d::norm(normal), 1.0, 1e-12);
  }
  // Hints carry over to the same triangles at moved positions.
  for (Vec3& x : m.positions) x = x + Vec3{0.01, 0.02, 0.0};
  const c4d::SurfaceProjector moved(m);
  EXPECT_EQ(moved.hint_of(5), 5);
  EXPECT_EQ(moved.mesh_triangle(moved.hint_of(17)), 17);
}

TEST(SurfaceWalk, ProjectorFallsBackToTheTreeFarFromTheWalk) {
  // Two parallel sheets 0.3 apart (separate components, edges 1 mm), and a zero-area triangle that
  // the projector leaves out.
  TriangleMesh m;
  for (double z : {0.0, 0.3})
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j) m.positions.push_back({double(i), double(j), z});
  for (std::uint32_t base : {0u, 25u})
    for (std::uint32_t i = 0; i < 4; ++i)
      for (std::uint32_t j = 0; j < 4; ++j) {
        const std::uint32_t a = base + 5 * i + j;
        m.triangles.push_back({a, a + 5, a + 6});
        m.triangles.push_back({a, a + 6, a + 1});
      }
  m.triangles.push_back({0, 1, 2});  // zero area
  const c4d::SurfaceProjector proj(m);
  EXPECT_EQ(proj.hint_of(64), -1);
  EXPECT_EQ(proj.hint_of(63), 63);
  // Near the lower sheet, walked from a lower triangle: trusted, the lower sheet.
  std::int32_t hint = 12;
  Vec3 q = proj.walk({2.2, 2.3, 0.04}, nullptr, &hint);
  EXPECT_NEAR(q.z, 0.0, 1e-12);
  EXPECT_LT(hint, 32);
  // Nearer the upper sheet, walked from the same lower triangle: the walk cannot leave the lower sheet
  // and ends 0.25 mm away; the tree finds the upper one.
  hint = 12;
  q = proj.walk({2.2, 2.3, 0.25}, nullptr, &hint);
  EXPECT_NEAR(q.z, 0.3, 1e-12);
  EXPECT_GE(hint, 32);
}

}  // namespace
