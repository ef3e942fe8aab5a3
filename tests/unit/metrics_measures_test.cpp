// Tests of the metrics library: analytic truths (sphere volume, genus of a torus, zero distance to
// one's own rings), invariance to rigid motion, and each fault of a hand-broken mesh.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <nlohmann/json.hpp>

#include "contour4d/core/errors.h"
#include "contour4d/metrics/conformity.h"
#include "contour4d/metrics/correspondence.h"
#include "contour4d/metrics/distance.h"
#include "contour4d/metrics/normal_deviation.h"
#include "contour4d/metrics/evaluation.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/metrics/volume.h"
#include "metrics_fixtures.h"
#include "cgal_self_intersections.h"

namespace c4d {
namespace {

bool has_fault(const std::vector<std::string>& faults, const std::string& needle) {
  for (const std::string& f : faults)
    if (f.find(needle) != std::string::npos) return true;
  return false;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += x + "\n";
  return s;
}

TriangleMesh rigid_motion(const TriangleMesh& m) {
  TriangleMesh out = m;
  const double a = 0.7, b = -0.4;
  for (Vec3& p : out.positions) {
    const Vec3 q{std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y, p.z};
    p = Vec3{q.x, std::cos(b) * q.y - std::sin(b) * q.z, std::sin(b) * q.y + std::cos(b) * q.z} +
        Vec3{12.5, -3.0, 40.0};
  }
  return out;
}

TEST(Topology, IcosphereIsAValidClosedSurfaceOfGenusZero) {
  const TriangleMesh m = test::icosphere(10.0, 3);
  const TopologyReport t = check_topology(m);
  EXPECT_TRUE(t.ok()) << joined(t.faults);
  EXPECT_TRUE(t.closed());
  EXPECT_TRUE(t.edge_manifold());
  EXPECT_TRUE(t.vertex_manifold());
  EXPECT_TRUE(t.consistently_oriented());
  EXPECT_TRUE(t.outward());
  EXPECT_TRUE(t.self_intersections_checked);
  EXPECT_EQ(t.self_intersections, 0u);
  ASSERT_EQ(t.components.size(), 1u);
  EXPECT_EQ(t.components[0].euler, 2);
  EXPECT_EQ(t.genus, 0);
  const double sphere = 4.0 / 3.0 * std::numbers::pi * 1000.0;
  EXPECT_NEAR(t.signed_volume, sphere, 0.02 * sphere);
  EXPECT_LT(t.signed_volume, sphere);  // an inscribed polyhedron
}

TEST(Topology, TorusHasGenusOne) {
  const TopologyReport t = check_topology(test::torus(10.0, 3.0, 40, 16));
  EXPECT_TRUE(t.ok()) << joined(t.faults);
  EXPECT_EQ(t.genus, 1);
  ASSERT_EQ(t.components.size(), 1u);
  EXPECT_EQ(t.components[0].euler, 0);
}

TEST(Topology, OneFlippedTriangleIsReported) {
  TriangleMesh m = test::icosphere(10.0, 2);
  std::swap(m.triangles[17][1], m.triangles[17][2]);
  const TopologyReport t = check_topology(m);
  EXPECT_EQ(t.flipped_triangles, 1u);
  EXPECT_EQ(t.misoriented_edges, 3u);
  EXPECT_TRUE(t.closed());
  EXPECT_FALSE(t.consistently_oriented());
  EXPECT_TRUE(has_fault(t.faults, "1 triangle oriented against its neighbours")) << joined(t.faults);
}

TEST(Topology, AHoleIsReported) {
  TriangleMesh m = test::icosphere(10.0, 2);
  m.triangles.erase(m.triangles.begin() + 5);
  const TopologyReport t = check_topology(m);
  EXPECT_EQ(t.boundary_edges, 3u);
  ASSERT_EQ(t.components.size(), 1u);
  EXPECT_EQ(t.components[0].boundary_loops, 1u);
  EXPECT_EQ(t.genus, 0);  // a sphere with one hole: χ = 1, b = 1
  EXPECT_TRUE(has_fault(t.faults, "3 boundary edges (a hole)")) << joined(t.faults);
}

TEST(Topology, InwardOrientationIsReported) {
  TriangleMesh m = test::icosphere(5.0, 1);
  for (Triangle& tr : m.triangles) std::swap(tr[1], tr[2]);
  const TopologyReport t = check_topology(m);
  EXPECT_TRUE(t.consistently_oriented());
  EXPECT_FALSE(t.outward());
  EXPECT_TRUE(has_fault(t.faults, "face inward")) << joined(t.faults);
}

TEST(Topology, SelfIntersectionsCountCrossingSpheresOnly) {
  TriangleMesh a = test::icosphere(5.0, 2);
  auto append = [](TriangleMesh& dst, const TriangleMesh& src) {
    const auto off = static_cast<std::uint32_t>(dst.positions.size());
    dst.positions.insert(dst.positions.end(), src.positions.begin(), src.positions.end());
    for (Triangle t : src.triangles) dst.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  };
  TriangleMesh apart = a;
  append(apart, test::icosphere(5.0, 2, {20, 0, 0}));
  const TopologyReport ta = check_topology(apart);
  EXPECT_TRUE(ta.ok()) << joined(ta.faults);
  EXPECT_EQ(ta.components.size(), 2u);
  EXPECT_EQ(ta.genus, 0);
  TriangleMesh crossing = a;
  append(crossing, test::icosphere(5.0, 2, {6, 0.3, 0.2}));
  const TopologyReport tc = check_topology(crossing);
  EXPECT_GT(tc.self_intersections, 0u);
  EXPECT_TRUE(has_fault(tc.faults, "of triangles intersect")) << joined(tc.faults);
  // Each pair is counted once: the count does not depend on the triangle order.
  TriangleMesh reversed = crossing;
  std::reverse(reversed.triangles.begin(), reversed.triangles.end());
  EXPECT_EQ(count_self_intersections(reversed), tc.self_intersections);
  // Restricted to flagged triangles: all flagged gives the full count, each sphere alone too (every
  // crossing pair has one triangle on each), neither none.
  const std::size_t half = a.triangles.size();
  std::vector<char> all(crossing.triangles.size(), 1), first(crossing.triangles.size(), 0),
      none(crossing.triangles.size(), 0);
  std::fill(first.begin(), first.begin() + static_cast<std::ptrdiff_t>(half), 1);
  std::vector<char> second(crossing.triangles.size(), 1);
  std::fill(second.begin(), second.begin() + static_cast<std::ptrdiff_t>(half), 0);
  EXPECT_EQ(count_self_intersections_of(crossing, all), tc.self_intersections);
  EXPECT_EQ(count_self_intersections_of(crossing, first), tc.self_intersections);
  EXPECT_EQ(count_self_intersections_of(crossing, second), tc.self_intersections);
  EXPECT_EQ(count_self_intersections_of(crossing, none), 0u);
  EXPECT_EQ(count_self_intersections_of(apart, std::vector<char>(apart.triangles.size(), 1)), 0u);
}

// Pairs through a vertex whose fan projects flat without folding are never tested (untangled_fans in
// topology.cpp); folded fans must still be found. Vertices pushed along the surface by up to three
// edges fold their fans over their neighbours': the count and the pairs equal CGAL's
// self_intersections on the same surface, under a rigid motion too.
TEST(Topology, SelfIntersectionsOfFoldedFansAgreeWithCgal) {
  const TriangleMesh sphere = test::icosphere(10.0, 3);
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> pick(0, sphere.positions.size() - 1);
  std::uniform_real_distribution<double> step(-4.5, 4.5);
  for (int trial = 0; trial < 6; ++trial) {
    TriangleMesh m = sphere;
    for (int k = 0; k < 3 * trial; ++k) {
      Vec3& p = m.positions[pick(rng)];
      p = 10.0 * normalized(p + Vec3{step(rng), step(rng), step(rng)});  // along the sphere
    }
    if (trial == 5) m.positions[7] = 0.1 * m.positions[7];  // a vertex pulled through to the middle
    std::vector<std::pair<std::size_t, std::size_t>> ours;
    const std::size_t n = count_self_intersections(m, &ours, m.triangles.size());
    const auto cgal = c4d::testing::self_intersecting_pairs(m);
    ASSERT_EQ(n, cgal.size()) << "trial " << trial;
    for (std::size_t k = 0; k < n; ++k) {
      EXPECT_EQ(ours[k].first, cgal[k][0]);
      EXPECT_EQ(ours[k].second, cgal[k][1]);
    }
    EXPECT_EQ(count_self_intersections(rigid_motion(m)), n) << "trial " << trial;
    EXPECT_EQ(count_self_intersections_of(m, std::vector<char>(m.triangles.size(), 1)), n) << "trial " << trial;
    if (trial > 0) {
      EXPECT_GT(n, 0u) << "trial " << trial;
    }
  }
  // A flat fan that turns the same way in every triangle but winds twice round its vertex: its
  // triangles overlap although none is flipped.
  TriangleMesh twice;
  twice.positions.push_back({0, 0, 0});
  for (int k = 0; k < 7; ++k) {
    const double a = 4.0 * std::numbers::pi * k / 7.0;
    twice.positions.push_back({std::cos(a), std::sin(a), 0.0});
  }
  for (std::uint32_t k = 0; k < 7; ++k) twice.triangles.push_back({0, 1 + k, 1 + (k + 1) % 7});
  const std::size_t n = count_self_intersections(twice);
  EXPECT_EQ(n, c4d::testing::self_intersecting_pairs(twice).size());
  EXPECT_GT(n, 0u);
}

// The box pairs come from a grid (topology.cpp, grid_overlapping_pairs) unless its cells are crowded,
// when CGAL's box search takes over: on soups of small triangles (the grid), of small triangles with a
// few large ones across them, and of triangles heaped in one spot (crowded), the count and the pairs
// equal CGAL's self_intersections, and the count restricted to flagged triangles equals the number of
// CGAL's pairs with a flagged triangle.
TEST(Topology, SelfIntersectionsOfTriangleSoupsAgreeWithCgal) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 6; ++trial) {
    std::uniform_real_distribution<double> where(0.0, trial >= 4 ? 0.5 : 30.0), size(-1.0, 1.0);
    TriangleMesh m;
    for (std::uint32_t k = 0; k < 600; ++k) {
      // Some triangles share a vertex (k % 7 == 1) or an edge (k % 11 == 3) with the one before and lie
      // beside it (those pairs never count).
      const bool vertex = k % 7 == 1, edge = !vertex && k % 11 == 3;
      const Vec3 c = vertex || edge ? m.positions.back() : Vec3{where(rng), where(rng), where(rng)};
      const double s = (trial % 2 == 1 && k % 100 == 0) ? 15.0 : 1.0;  // odd trials: six large triangles
      const auto next = static_cast<std::uint32_t>(m.positions.size());
      for (int corner = 0; corner < 3; ++corner) m.positions.push_back(c + s * Vec3{size(rng), size(rng), size(rng)});
      Triangle t{next, next + 1, next + 2};
      if (vertex) t[0] = m.triangles.back()[1];
      if (edge) t = {m.triangles.back()[0], m.triangles.back()[2], next};
      m.triangles.push_back(t);
    }
    std::vector<std::pair<std::size_t, std::size_t>> ours;
    const std::size_t n = count_self_intersections(m, &ours, std::numeric_limits<std::size_t>::max());
    const auto cgal = c4d::testing::self_intersecting_pairs(m);
    ASSERT_EQ(n, cgal.size()) << "trial " << trial;
    ASSERT_EQ(ours.size(), n) << "trial " << trial;
    ASSERT_GT(n, 0u) << "trial " << trial;
    for (std::size_t k = 0; k < n; ++k) {
      EXPECT_EQ(ours[k].first, cgal[k][0]) << "trial " << trial;
      EXPECT_EQ(ours[k].second, cgal[k][1]) << "trial " << trial;
    }
    std::vector<char> only(m.triangles.size(), 0);
    for (std::size_t t = 0; t < only.size(); t += 3) only[t] = 1;
    std::size_t with_flagged = 0;
    for (const auto& pr : cgal) with_flagged += only[pr[0]] || only[pr[1]];
    EXPECT_EQ(count_self_intersections_of(m, only), with_flagged) << "trial " << trial;
  }
}

TEST(Topology, IntersectsAnyAgreesWithTheCountOfEachTriangle) {
  // Two crossing spheres: for each triangle of the first, intersects_any against every triangle is true
  // exactly when count_self_intersections_of finds a pair with it (shared edges and vertices excluded).
  TriangleMesh m = test::icosphere(5.0, 2);
  const TriangleMesh b = test::icosphere(5.0, 2, {6, 0.3, 0.2});
  const auto off = static_cast<std::uint32_t>(m.positions.size());
  const std::size_t half = m.triangles.size();
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (Triangle t : b.triangles) m.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  std::vector<std::uint32_t> all(m.triangles.size());
  for (std::uint32_t f = 0; f < all.size(); ++f) all[f] = f;
  std::size_t crossing = 0;
  for (std::uint32_t f = 0; f < half; ++f) {
    std::vector<char> only(m.triangles.size(), 0);
    only[f] = 1;
    const bool expected = count_self_intersections_of(m, only) > 0;
    EXPECT_EQ(intersects_any(m.positions, m.triangles, {f}, all), expected) << "triangle " << f;
    crossing += expected;
  }
  EXPECT_GT(crossing, 0u);
  // A vertex's ring with its neighbours: never intersecting (they share vertices and edges only).
  std::vector<std::uint32_t> ring;
  for (std::uint32_t f = 0; f < half; ++f)
    for (std::uint32_t v : m.triangles[f])
      if (v == 0) ring.push_back(f);
  EXPECT_FALSE(
      intersects_any(m.positions, m.triangles, ring, std::vector<std::uint32_t>(all.begin(), all.begin() + half)));
  // Two ring triangles folded onto each other are found among `these` alone.
  TriangleMesh fold;
  fold.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 0}};
  fold.triangles = {{0, 1, 2}, {0, 1, 3}};
  EXPECT_TRUE(intersects_any(fold.positions, fold.triangles, {0, 1}, {}));
  EXPECT_FALSE(intersects_any(fold.positions, fold.triangles, {0}, {}));
}

TEST(Topology, NonManifoldAndDegenerateElementsAreReported) {
  // Two tetrahedra touching at one vertex.
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  TopologyReport t = check_topology(m);
  EXPECT_EQ(t.nonmanifold_vertices, 1u);
  EXPECT_TRUE(has_fault(t.faults, "1 non-manifold vertex")) << joined(t.faults);
  // A fin: a third triangle on an edge.
  TriangleMesh fin = test::icosphere(3.0, 1);
  fin.positions.push_back({10, 10, 10});
  const Triangle& t0 = fin.triangles[0];
  fin.triangles.push_back({t0[0], t0[1], static_cast<std::uint32_t>(fin.positions.size() - 1)});
  t = check_topology(fin);
  EXPECT_EQ(t.nonmanifold_edges, 1u);
  EXPECT_EQ(t.genus, -1);
  // A degenerate triangle, a duplicate vertex (unreferenced) and an invalid index.
  TriangleMesh d = test::icosphere(3.0, 1);
  d.positions.push_back(d.positions[0]);
  d.positions.push_back(0.5 * (d.positions[1] + d.positions[2]));
  d.triangles.push_back({1, 2, static_cast<std::uint32_t>(d.positions.size() - 1)});
  d.triangles.push_back({0, 1, 999});
  t = check_topology(d);
  EXPECT_EQ(t.degenerate_triangles, 1u);
  EXPECT_EQ(t.duplicate_vertices, 1u);
  EXPECT_EQ(t.unreferenced_vertices, 1u);
  EXPECT_EQ(t.invalid_triangles, 1u);
  EXPECT_TRUE(has_fault(t.faults, "1 degenerate triangle (zero area)")) << joined(t.faults);
  EXPECT_TRUE(has_fault(t.faults, "1 duplicate vertex")) << joined(t.faults);
  EXPECT_TRUE(has_fault(check_topology(TriangleMesh{}).faults, "no triangles"));
}

// The counts-only check (what the surface stage runs on its own meshes) counts what the full check
// counts, on good meshes and on each fault: holes, flips, fins, pinched vertices, inward, degenerate.
TEST(Topology, CountsOnlyAgreesWithTheFullCheck) {
  std::vector<TriangleMesh> meshes = {test::icosphere(10.0, 2), test::torus(10.0, 3.0, 40, 16)};
  TriangleMesh m = test::icosphere(10.0, 2);
  m.triangles.erase(m.triangles.begin() + 5);  // a hole
  meshes.push_back(m);
  m = test::icosphere(10.0, 2);
  std::swap(m.triangles[17][1], m.triangles[17][2]);  // a flipped triangle
  meshes.push_back(m);
  m = test::icosphere(3.0, 1);
  m.positions.push_back({10, 10, 10});
  m.triangles.push_back({m.triangles[0][0], m.triangles[0][1], static_cast<std::uint32_t>(m.positions.size() - 1)});
  meshes.push_back(m);  // a fin
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  meshes.push_back(m);  // two tetrahedra on one vertex
  m = test::icosphere(5.0, 1);
  for (Triangle& tr : m.triangles) std::swap(tr[1], tr[2]);  // inward
  m.triangles.push_back({0, 1, 999});                        // an invalid index
  meshes.push_back(m);
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const TopologyReport full = check_topology(meshes[k]);
    const TopologyReport fast = check_topology(meshes[k], {.counts_only = true});
    SCOPED_TRACE("mesh " + std::to_string(k));
    EXPECT_EQ(fast.boundary_edges, full.boundary_edges);
    EXPECT_EQ(fast.nonmanifold_edges, full.nonmanifold_edges);
    EXPECT_EQ(fast.nonmanifold_vertices, full.nonmanifold_vertices);
    EXPECT_EQ(fast.misoriented_edges, full.misoriented_edges);
    EXPECT_EQ(fast.degenerate_triangles, full.degenerate_triangles);
    EXPECT_EQ(fast.invalid_triangles, full.invalid_triangles);
    EXPECT_EQ(fast.edges, full.edges);
    EXPECT_EQ(fast.euler, full.euler);
    EXPECT_EQ(fast.components.size(), full.components.size());
    EXPECT_EQ(fast.signed_volume, full.signed_volume);
    EXPECT_EQ(fast.self_intersections, full.self_intersections);
    EXPECT_EQ(fast.closed_manifold(), full.closed_manifold());
    long euler = 0;
    for (const ComponentTopology& c : full.components) euler += c.euler;
    if (full.vertex_manifold()) {
      EXPECT_EQ(full.euler, euler);
    }
  }
}

TEST(Quality, IcosphereAnglesArePlausibleAndRigidInvariant) {
  const TriangleMesh m = test::icosphere(10.0, 3);
  const AngleQuality q = angle_quality(m);
  EXPECT_EQ(q.triangles, m.triangles.size());
  EXPECT_GT(q.pct_40_80, 95.0);
  EXPECT_NEAR(q.pct_40_80, q.pct_40_50 + q.pct_50_60 + q.pct_60_70 + q.pct_70_80, 1e-9);
  EXPECT_EQ(q.bad_triangles, 0u);
  EXPECT_GT(q.min_angle_deg, 45.0);
  EXPECT_LT(q.max_angle_deg, 80.0);
  const AngleQuality r = angle_quality(rigid_motion(m));
  EXPECT_NEAR(r.min_angle_deg, q.min_angle_deg, 1e-9);
  EXPECT_NEAR(r.pct_40_80, q.pct_40_80, 1e-9);
  // A needle triangle is bad.
  TriangleMesh needle;
  needle.positions = {{0, 0, 0}, {10, 0, 0}, {5, 0.5, 0}};
  needle.triangles = {{0, 1, 2}};
  const AngleQuality n = angle_quality(needle);
  EXPECT_EQ(n.bad_triangles, 1u);
  EXPECT_NEAR(n.bad_pct, 100.0, 1e-12);
  EXPECT_NEAR(n.min_angle_deg, std::atan(0.1) * 180 / std::numbers::pi, 1e-9);
}

// angles_40_80 counts per triangle what angle_quality's pct_40_80 counts over the mesh.
TEST(Quality, AnglesIn40To80PerTriangleAgreeWithTheMeshShare) {
  const TriangleMesh m = rigid_motion(test::icosphere(10.0, 2));
  std::size_t good = 0;
  for (const Triangle& t : m.triangles)
    good += static_cast<std::size_t>(angles_40_80(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  EXPECT_NEAR(100.0 * static_cast<double>(good) / static_cast<double>(3 * m.triangles.size()),
              angle_quality(m).pct_40_80, 1e-9);
  EXPECT_EQ(angles_40_80({0, 0, 0}, {1, 0, 0}, {0.5, 0.8660254037844386, 0}), 3);  // equilateral
  EXPECT_EQ(angles_40_80({0, 0, 0}, {10, 0, 0}, {5, 0.5, 0}), 0);                  // needle: 5.7°, 5.7°, 168.6°
  EXPECT_EQ(angles_40_80({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 2);                     // 90°, 45°, 45°
  EXPECT_EQ(angles_40_80({0, 0, 0}, {1, 0, 0}, {2, 0, 0}), 0);                     // zero area
}

TEST(Conformity, ContoursThatAreTheMeshRingsAreAtZeroDistance) {
  const TriangleMesh m = test::ring_sphere(20.0, 9, 48);
  const Frame f = test::ring_contours(m, 9, 48);
  const DistanceStats s = contour_conformity(m, f);
  EXPECT_GT(s.samples, 1000u);
  EXPECT_LT(s.max, 1e-9);
  EXPECT_LT(s.mean, 1e-9);
  // Rings 1 mm outside: every sample is about 1 mm away (less near the flat facets' corners).
  Frame out = f;
  for (Slice& sl : out.slices)
    for (Contour& c : sl.contours)
      for (Vec3& p : c.points) {
        const double rr = std::hypot(p.x, p.y);
        p.x *= (rr + 1.0) / rr;
        p.y *= (rr + 1.0) / rr;
      }
  const DistanceStats o = contour_conformity(m, out);
  EXPECT_GT(o.mean, 0.5);
  EXPECT_LT(o.max, 1.0 + 1e-9);
}

TEST(Distance, SurfacesAgainstThemselvesAndAConcentricSphere) {
  const TriangleMesh a = test::icosphere(10.0, 4), b = test::icosphere(11.0, 4);
  const SurfaceComparison self = compare_surfaces(a, a);
  EXPECT_LT(self.whole.hausdorff, 1e-9);
  SurfaceDistanceOptions opt;
  opt.use_slab = true;
  opt.slab = {{0, 0, 1}, -5.0, 5.0};
  const SurfaceComparison c = compare_surfaces(a, b, opt);
  EXPECT_NEAR(c.whole.mesh_to_truth.mean, 1.0, 0.05);
  EXPECT_NEAR(c.whole.truth_to_mesh.mean, 1.0, 0.05);
  EXPECT_GE(c.whole.hausdorff, c.whole.mesh_to_truth.max);
  EXPECT_GE(c.whole.mesh_to_truth.rms, c.whole.mesh_to_truth.mean);
  ASSERT_TRUE(c.has_slab);
  EXPECT_LT(c.slab.mesh_to_truth.samples, c.whole.mesh_to_truth.samples);
  EXPECT_GT(c.slab.mesh_to_truth.samples, 0u);
  // Swapping the surfaces swaps the directions.
  const SurfaceComparison d = compare_surfaces(b, a);
  EXPECT_DOUBLE_EQ(d.whole.mesh_to_truth.mean, c.whole.truth_to_mesh.mean);
  EXPECT_DOUBLE_EQ(d.whole.hausdorff, c.whole.hausdorff);
  // Rigid motion of both leaves the distances (almost) unchanged.
  const SurfaceComparison e = compare_surfaces(rigid_motion(a), rigid_motion(b));
  EXPECT_NEAR(e.whole.mesh_to_truth.mean, c.whole.mesh_to_truth.mean, 1e-9);
  EXPECT_THROW(compare_surfaces(a, TriangleMesh{}), InvalidInput);
}

TEST(Distance, SamplesCoverTheAreaExactly) {
  const TriangleMesh m = test::icosphere(10.0, 2);
  double area = 0.0;
  for (const SurfaceSample& s : sample_surface(m, {0.7, 16})) area += s.area;
  EXPECT_NEAR(area, surface_area(m), 1e-9 * area);
}

TEST(Volume, AreasWithHolesAndDiscRule) {
  Slice s;
  Contour outer, inner;
  outer.points = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  inner.points = {{3, 3, 0}, {3, 7, 0}, {7, 7, 0}, {7, 3, 0}};  // either orientation
  s.contours = {outer, inner};
  EXPECT_NEAR(enclosed_area(s, {1, 0, 0}, {0, 1, 0}), 84.0, 1e-12);

  // Ten circles of radius 10 at z = 0..9: discs give 10 slices × 1 mm, trapezoids 9 mm.
  Frame f;
  for (int i = 0; i < 10; ++i) {
    Slice sl;
    sl.id = i;
    Contour c;
    for (int k = 0; k < 360; ++k)
      c.points.push_back(
          {10 * std::cos(k * std::numbers::pi / 180), 10 * std::sin(k * std::numbers::pi / 180), double(i)});
    sl.contours.push_back(c);
    f.slices.push_back(sl);
  }
  const std::vector<DiscVolume> v = simpson_volumes(test::z_sequence({f}));
  ASSERT_EQ(v.size(), 1u);
  const double area = v[0].slices[0].area;
  EXPECT_NEAR(area, 100 * std::numbers::pi, 0.01 * 100);
  EXPECT_NEAR(v[0].volume, 10 * area, 1e-9);
  EXPECT_NEAR(v[0].trapezoid_volume, 9 * area, 1e-9);

  const EjectionFraction ef = ejection_fraction({100, 70, 50, 80});
  EXPECT_EQ(ef.ed_frame, 0);
  EXPECT_EQ(ef.es_frame, 2);
  EXPECT_DOUBLE_EQ(ef.ef_pct, 50.0);
}

TEST(Volume, SimpsonOfASphereIsCloseToItsMeshVolume) {
  const TriangleMesh m = test::ring_sphere(20.0, 19, 96);
  const std::vector<DiscVolume> v = simpson_volumes(test::z_sequence({test::ring_contours(m, 19, 96)}));
  const double mesh = signed_volume(m);
  EXPECT_NEAR(v[0].volume, mesh, 0.05 * mesh);
}

TEST(Correspondence, BreathingSphereIsFineAndAShuffledFrameIsFound) {
  const TriangleMesh base = test::icosphere(20.0, 3);
  std::vector<TriangleMesh> frames;
  for (int f = 0; f < 6; ++f) frames.push_back(test::breathe(base, f));
  const CorrespondenceReport ok = check_correspondence(frames);
  EXPECT_TRUE(ok.ok()) << joined(ok.faults);
  for (double c : ok.median_edge_change_pct) EXPECT_LT(c, 20.0);

  frames[3] = test::shuffle_vertices(frames[3]);
  const CorrespondenceReport bad = check_correspondence(frames);
  EXPECT_TRUE(bad.same_vertex_count);
  EXPECT_TRUE(bad.same_triangles);
  EXPECT_EQ(bad.suspicious_frames, std::vector<int>{3});
  EXPECT_GT(bad.median_edge_change_pct[3], 200.0);
  EXPECT_TRUE(has_fault(bad.faults, "vertex correspondence suspicious: frame 3")) << joined(bad.faults);

  // Two frames: the reference is frame 0.
  const CorrespondenceReport two = check_correspondence({frames[0], frames[3]});
  EXPECT_EQ(two.suspicious_frames, std::vector<int>{1});

  // Different triangles.
  std::vector<TriangleMesh> diff = {frames[0], frames[1], frames[2]};
  std::swap(diff[2].triangles[4][0], diff[2].triangles[4][1]);
  const CorrespondenceReport d = check_correspondence(diff);
  EXPECT_FALSE(d.same_triangles);
  EXPECT_EQ(d.first_differing_frame, 2);
  EXPECT_TRUE(has_fault(d.faults, "triangle 4")) << joined(d.faults);
}

TEST(Evaluation, EndToEndIsCleanAndThreadCountIndependent) {
  const int rings = 9, per = 48;
  MeshFrames meshes;
  std::vector<Frame> cf;
  for (int f = 0; f < 4; ++f) {
    const TriangleMesh m = test::breathe(test::ring_sphere(20.0, rings, per), f);
    meshes.meshes.push_back(m);
    meshes.times_ms.push_back(40.0 * f);
    cf.push_back(test::ring_contours(m, rings, per));
  }
  const Sequence seq = test::z_sequence(cf);
  const Evaluation ev = evaluate(meshes, &seq, &meshes);
  EXPECT_TRUE(ev.faults.empty()) << joined(ev.faults);
  EXPECT_FALSE(ev.has_topology_fault());
  ASSERT_EQ(ev.frames.size(), 4u);
  for (const FrameEvaluation& fe : ev.frames) {
    ASSERT_TRUE(fe.conformity && fe.accuracy && fe.simpson && fe.contours_to_truth);
    EXPECT_LT(fe.conformity->max, 1e-9);
    EXPECT_LT(fe.accuracy->whole.hausdorff, 1e-9);
    EXPECT_TRUE(fe.accuracy->has_slab);
    EXPECT_NEAR(fe.simpson->volume, fe.volume, 0.15 * fe.volume);
  }
  EXPECT_EQ(ev.mesh_ef.ed_frame, 0);
  ASSERT_TRUE(ev.simpson_ef);
  EXPECT_EQ(ev.simpson_ef->ed_frame, 0);

  const std::string json = format_evaluation_json(ev);
  std::string single;
  tbb::task_arena one(1);
  one.execute([&] { single = format_evaluation_json(evaluate(meshes, &seq, &meshes)); });
  EXPECT_EQ(json, single);
  const auto j = nlohmann::json::parse(json);
  EXPECT_EQ(j["format"], "contour4d-evaluation");
  EXPECT_EQ(j["units"]["volume"], "mm³");
  EXPECT_EQ(j["summary"]["correspondence"], "yes");
  EXPECT_EQ(j["frames"].size(), 4u);
  EXPECT_TRUE(j["frames"][0].contains("accuracy_slab"));
  EXPECT_NE(format_evaluation_table(ev).find("no faults"), std::string::npos);
}

}  // namespace
}  // namespace c4d

namespace c4d {
namespace {

// Facet normals against a reference (normal_deviation.h): zero against itself, whatever rigid motion
// both share; a flat-faceted sphere against a finer one of the same radius stays within its facets' half
// angle; rough vertices tilt facets by degrees that distances of a few hundredths of a mm do not show; an
// inside-out copy is 180° off.
TEST(NormalDeviation, ZeroOnItselfBoundedOnFinerFacetsLargeOnNoiseAndFlips) {
  const TriangleMesh coarse = test::icosphere(10.0, 3), fine = test::icosphere(10.0, 5);
  const NormalDeviation self = normal_deviation(coarse, coarse);
  EXPECT_EQ(self.triangles, coarse.triangles.size());
  EXPECT_LT(self.max_deg, 1e-6);
  const NormalDeviation facets = normal_deviation(coarse, fine);
  EXPECT_LT(facets.max_deg, 8.0);  // the coarse facets span under 10° of the sphere
  TriangleMesh noisy = fine;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Vec3& p : noisy.positions) p = p + Vec3{u(rng), u(rng), u(rng)};
  EXPECT_GT(normal_deviation(noisy, fine).p99_deg, 5.0);
  TriangleMesh flipped = coarse;
  for (Triangle& t : flipped.triangles) std::swap(t[1], t[2]);
  EXPECT_GT(normal_deviation(flipped, coarse).median_deg, 179.0);
  EXPECT_THROW(normal_deviation(coarse, TriangleMesh{}), InvalidInput);
}

}  // namespace
}  // namespace c4d
