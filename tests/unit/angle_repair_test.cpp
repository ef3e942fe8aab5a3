// Small-angle repair (surface/angle_repair.h): properties on a plane and a sphere.
#include "contour4d/surface/angle_repair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contour4d/core/mesh.h"
#include "contour4d/metrics/topology.h"

namespace {

using c4d::Triangle;
using c4d::Vec3;

// A regular n×n grid of the unit square in z = 0, two triangles per cell.
c4d::TriangleMesh grid(int n, double h) {
  c4d::TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.push_back({i * h, j * h, 0});
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

double min_angle(const c4d::TriangleMesh& m) {
  double a = 180;
  for (const Triangle& t : m.triangles)
    a = std::min(a, c4d::min_angle_deg(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  return a;
}

std::vector<char> boundary(int n) {
  std::vector<char> fixed(static_cast<std::size_t>((n + 1) * (n + 1)), 0);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      if (i == 0 || j == 0 || i == n || j == n) fixed[static_cast<std::size_t>(j * (n + 1) + i)] = 1;
  return fixed;
}

}  // namespace

TEST(AngleRepair, MinAngleOfKnownTriangles) {
  EXPECT_NEAR(c4d::min_angle_deg({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}), 60.0, 1e-9);
  EXPECT_NEAR(c4d::min_angle_deg({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 45.0, 1e-9);
  EXPECT_EQ(c4d::min_angle_deg({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), 0.0);
}

TEST(AngleRepair, PushedVerticesComeBackOnThePlaneAndFixedOnesStay) {
  const int n = 8;
  c4d::TriangleMesh m = grid(n, 1.0);
  // Squeeze two interior vertices next to their neighbours: thin triangles.
  m.positions[static_cast<std::size_t>(3 * (n + 1) + 3)] = {3.85, 3.1, 0};
  m.positions[static_cast<std::size_t>(5 * (n + 1) + 4)] = {4.05, 5.9, 0};
  const auto before = m.positions;
  ASSERT_LT(min_angle(m), 10.0);
  const auto fixed = boundary(n);
  auto plane = [](std::uint32_t, Vec3 p) { return Vec3{p.x, p.y, 0}; };
  const std::size_t moves = c4d::repair_small_angles(m.positions, m.triangles, fixed, plane);
  EXPECT_GT(moves, 0u);
  EXPECT_GT(min_angle(m), 30.0);  // the default target
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_EQ(m.positions[v].z, 0.0);
    if (fixed[v]) {
      EXPECT_TRUE(m.positions[v] == before[v]);
    }
  }
  // Deterministic: the same input gives the same positions.
  c4d::TriangleMesh again = grid(n, 1.0);
  again.positions = before;
  c4d::repair_small_angles(again.positions, again.triangles, fixed, plane);
  for (std::size_t v = 0; v < m.positions.size(); ++v) EXPECT_TRUE(again.positions[v] == m.positions[v]);
}

// The ring-crossing test bins the triangles in a dense block of cells over the mesh's extent, coarsened
// when the extent is huge against the edges: a far, separate patch then only adds candidates, and the
// repaired grid is the same to the bit.
TEST(AngleRepair, AFarPatchChangesNothingOnTheGrid) {
  const int n = 8;
  c4d::TriangleMesh m = grid(n, 1.0);
  m.positions[static_cast<std::size_t>(3 * (n + 1) + 3)] = {3.85, 3.1, 0};
  m.positions[static_cast<std::size_t>(5 * (n + 1) + 4)] = {4.05, 5.9, 0};
  c4d::TriangleMesh far = m;
  const auto base = static_cast<std::uint32_t>(far.positions.size());
  for (const Vec3& p : m.positions) far.positions.push_back({p.x + 1e6, p.y - 2e5, p.z + 3e5});
  for (const Triangle& t : m.triangles) far.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  std::vector<char> fixed = boundary(n);
  std::vector<char> fixed_far = fixed;
  fixed_far.insert(fixed_far.end(), fixed.size(), 1);  // the far patch stays
  // Moves stay in each patch's plane (tangent steps of a flat patch), so the snap keeps them as they are.
  auto keep = [](std::uint32_t, Vec3 p) { return p; };
  const std::size_t moves = c4d::repair_small_angles(m.positions, m.triangles, fixed, keep);
  const std::size_t moves_far = c4d::repair_small_angles(far.positions, far.triangles, fixed_far, keep);
  EXPECT_GT(moves, 0u);
  EXPECT_EQ(moves, moves_far);
  for (std::size_t v = 0; v < m.positions.size(); ++v) EXPECT_TRUE(far.positions[v] == m.positions[v]) << v;
}

TEST(AngleRepair, GoodMeshIsLeftAlone) {
  c4d::TriangleMesh m = grid(6, 1.0);  // right isosceles triangles: 45° everywhere
  const auto before = m.positions;
  c4d::AngleRepairOptions o;
  o.target_deg = 40;
  EXPECT_EQ(c4d::repair_small_angles(
                m.positions, m.triangles, boundary(6), [](std::uint32_t, Vec3 p) { return p; }, o),
            0u);
  for (std::size_t v = 0; v < m.positions.size(); ++v) EXPECT_TRUE(m.positions[v] == before[v]);
}

TEST(AngleRepair, OpensASliverThatTurnedOverTowardsTheSurfacesSide) {
  // Vertex (4, 3) pushed just across the diagonal (3, 3)–(4, 4) of its cell: its triangle there is a
  // 178° sliver, turned over. Its own normal points down, so only the vertex normals tell which way
  // opening it is right (biv-me frame 6 kept such a 3.2° triangle).
  const int n = 8;
  c4d::TriangleMesh m = grid(n, 1.0);
  const std::size_t v = 3 * (n + 1) + 4;
  m.positions[v] = {3.49, 3.51, 0};
  const Triangle sliver{static_cast<std::uint32_t>(3 * (n + 1) + 3), static_cast<std::uint32_t>(v),
                        static_cast<std::uint32_t>(4 * (n + 1) + 4)};
  auto normal_z = [&](const Triangle& t) {
    return c4d::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]).z;
  };
  ASSERT_LT(normal_z(sliver), 0.0);
  ASSERT_LT(min_angle(m), 2.0);
  auto plane = [](std::uint32_t, Vec3 p) { return Vec3{p.x, p.y, 0}; };
  c4d::repair_small_angles(m.positions, m.triangles, boundary(n), plane);
  EXPECT_GT(min_angle(m), 30.0);
  for (const Triangle& t : m.triangles) EXPECT_GT(normal_z(t), 0.0);  // every triangle faces up again
}

TEST(AngleRepair, MovesStayOnACurvedSurfaceAndNeverFold) {
  // The grid wrapped on a cylinder of radius 3 (axis y): the snap projects onto it.
  const int n = 10;
  c4d::TriangleMesh m = grid(n, 0.5);
  auto wrap = [](Vec3 p) { return Vec3{3 * std::sin(p.x / 3), p.y, 3 * std::cos(p.x / 3)}; };
  for (Vec3& p : m.positions) p = wrap(p);
  m.positions[static_cast<std::size_t>(4 * (n + 1) + 5)] = wrap({2.92, 2.08, 0});
  auto cylinder = [](std::uint32_t, Vec3 p) {
    const double r = std::hypot(p.x, p.z);
    return Vec3{3 * p.x / r, p.y, 3 * p.z / r};
  };
  const auto fixed = boundary(n);
  std::vector<Vec3> normals_before;
  for (const Triangle& t : m.triangles)
    normals_before.push_back(c4d::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
  const double before = min_angle(m);
  c4d::repair_small_angles(m.positions, m.triangles, fixed, cylinder);
  ASSERT_LT(before, 15.0);
  EXPECT_GT(min_angle(m), 30.0);
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const Triangle& t = m.triangles[f];
    const Vec3 nn = c4d::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    EXPECT_GT(c4d::dot(nn, normals_before[f]), 0.0);
  }
  for (const Vec3& p : m.positions) EXPECT_NEAR(std::hypot(p.x, p.z), 3.0, 1e-9);
}

TEST(AngleRepair, UntangleOpensAFoldedPatch) {
  // A grid on a plane; one interior vertex pushed past two of its neighbours folds its triangles
  // over theirs.
  const int n = 8;
  c4d::TriangleMesh m = grid(n, 1.0);
  for (Vec3& p : m.positions) p.z = 0.05 * p.x * p.y;  // slightly curved, so overlaps are crossings
  const std::size_t v = static_cast<std::size_t>(4 * (n + 1) + 4);
  m.positions[v] = {5.6, 5.5, 0.05 * 5.6 * 5.5};
  ASSERT_GT(c4d::count_self_intersections(m), 0u);
  auto saddle = [](std::uint32_t, Vec3 p) { return Vec3{p.x, p.y, 0.05 * p.x * p.y}; };
  const auto fixed = boundary(n);
  EXPECT_EQ(c4d::untangle(m.positions, m.triangles, fixed, saddle), 0u);
  EXPECT_EQ(c4d::count_self_intersections(m), 0u);
  for (std::size_t w = 0; w < m.positions.size(); ++w) {
    EXPECT_NEAR(m.positions[w].z, 0.05 * m.positions[w].x * m.positions[w].y, 1e-12);
  }
}

TEST(AngleRepair, UntangleLeavesAGoodMeshAlone) {
  c4d::TriangleMesh m = grid(6, 1.0);
  const auto before = m.positions;
  EXPECT_EQ(c4d::untangle(m.positions, m.triangles, boundary(6), [](std::uint32_t, Vec3 p) { return p; }), 0u);
  for (std::size_t v = 0; v < m.positions.size(); ++v) EXPECT_TRUE(m.positions[v] == before[v]);
}
