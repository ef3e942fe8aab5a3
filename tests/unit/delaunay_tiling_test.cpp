// Tests of tile_slices_delaunay (Lim et al. 2014, "Reconstruction from Segmented Contour Lines"):
// the band keeps every contour edge once, closes with caps into an outward 2-manifold without flat
// or degenerate triangles, and its volume matches analytic solids.
#include "contour4d/surface/delaunay_tiling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "contour4d/core/errors.h"
#include "contour4d/metrics/topology.h"

namespace {

using c4d::DelaunayTiling;
using c4d::Triangle;
using c4d::Vec2;
using c4d::Vec3;
using Polygons = std::vector<std::vector<Vec2>>;

constexpr double kPi = std::numbers::pi;

// n points on an ellipse (semi-axes a, b, rotated by rot), counter-clockwise unless cw.
std::vector<Vec2> ellipse(double cx, double cy, double a, double b, double rot, int n, bool cw = false,
                          double phase = 0.0) {
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double t = phase + 2.0 * kPi * i / n;
    const double x = a * std::cos(t), y = b * std::sin(t);
    p.push_back({cx + std::cos(rot) * x - std::sin(rot) * y, cy + std::sin(rot) * x + std::cos(rot) * y});
  }
  if (cw) std::reverse(p.begin(), p.end());
  return p;
}
std::vector<Vec2> circle(double cx, double cy, double r, int n, bool cw = false) {
  return ellipse(cx, cy, r, r, 0.0, n, cw);
}

double signed_area(const Polygons& polygons) {
  double a = 0.0;
  for (const auto& p : polygons)
    for (std::size_t i = 0; i < p.size(); ++i) a += 0.5 * c4d::cross(p[i], p[(i + 1) % p.size()]);
  return a;
}

// Positions of all ids: lower vertices at 0, upper at gap, then the new points.
std::vector<Vec3> positions(const Polygons& lower, const Polygons& upper, double gap, const DelaunayTiling& t) {
  std::vector<Vec3> pos;
  for (const auto& p : lower)
    for (Vec2 q : p) pos.push_back({q.x, q.y, 0.0});
  for (const auto& p : upper)
    for (Vec2 q : p) pos.push_back({q.x, q.y, gap});
  pos.insert(pos.end(), t.points.begin(), t.points.end());
  return pos;
}

// Ids of each polygon (lower first, then upper).
std::vector<std::vector<std::uint32_t>> polygon_ids(const Polygons& lower, const Polygons& upper) {
  std::vector<std::vector<std::uint32_t>> ids;
  std::uint32_t next = 0;
  for (const Polygons* side : {&lower, &upper})
    for (const auto& p : *side) {
      ids.emplace_back();
      for (std::size_t i = 0; i < p.size(); ++i) ids.back().push_back(next++);
    }
  return ids;
}

// Properties 1-3 of the contract, for polygons given in the stated orientation.
void expect_valid_band(const Polygons& lower, const Polygons& upper, double gap, const DelaunayTiling& t) {
  const auto pos = positions(lower, upper, gap, t);
  for (const std::string& w : t.warnings) ADD_FAILURE() << "warning: " << w;
  EXPECT_EQ(t.flat_triangles, 0u);
  EXPECT_LE(t.crossing_points, t.points.size());
  // New points strictly between the slices: never on a contour.
  for (const Vec3& p : t.points) {
    EXPECT_GT(p.z, 0.0);
    EXPECT_LT(p.z, gap);
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const Triangle& tri : t.triangles) {
    for (std::uint32_t v : tri) ASSERT_LT(v, pos.size());
    const Vec3 a = pos[tri[0]], b = pos[tri[1]], c = pos[tri[2]];
    EXPECT_GT(c4d::norm(c4d::cross(b - a, c - a)), 1e-9) << "degenerate triangle";
    EXPECT_FALSE(a.z == b.z && b.z == c.z) << "flat triangle at height " << a.z;
    for (int k = 0; k < 3; ++k) directed[{tri[k], tri[(k + 1) % 3]}] += 1;
  }
  // Contour edges: exactly once, lower as given (the lower cap runs it backwards), upper reversed.
  const auto ids = polygon_ids(lower, upper);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> contour;
  for (std::size_t p = 0; p < ids.size(); ++p) {
    const bool is_lower = p < lower.size();
    for (std::size_t i = 0; i < ids[p].size(); ++i) {
      std::uint32_t a = ids[p][i], b = ids[p][(i + 1) % ids[p].size()];
      if (!is_lower) std::swap(a, b);
      const auto it = directed.find({a, b});
      EXPECT_EQ(it == directed.end() ? 0 : it->second, 1) << "contour edge " << a << "-" << b;
      EXPECT_EQ(directed.count({b, a}), 0u) << "contour edge " << a << "-" << b << " used backwards";
      contour[{std::min(a, b), std::max(a, b)}] = 1;
    }
  }
  // Every other edge: once in each direction.
  for (const auto& [e, n] : directed) {
    if (contour.count({std::min(e.first, e.second), std::max(e.first, e.second)})) continue;
    EXPECT_EQ(n, 1) << "edge " << e.first << "-" << e.second;
    EXPECT_EQ(directed.count({e.second, e.first}), 1u) << "edge " << e.first << "-" << e.second << " on the boundary";
  }
}

// Volume of band + caps by the divergence theorem with F = (0, 0, z): the lower cap adds nothing,
// the upper cap gap · area(upper).
double band_volume(const Polygons& lower, const Polygons& upper, double gap, const DelaunayTiling& t) {
  const auto pos = positions(lower, upper, gap, t);
  double v = gap * signed_area(upper);
  for (const Triangle& tri : t.triangles) {
    const Vec3 a = pos[tri[0]], b = pos[tri[1]], c = pos[tri[2]];
    const double projected = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    v += projected * (a.z + b.z + c.z) / 3.0;
  }
  return v;
}

// Band plus fan caps (convex polygons) or annulus caps: a closed mesh for check_mesh.
struct Cap {
  std::vector<std::uint32_t> outer;
  std::vector<std::uint32_t> hole;  // as given (clockwise), same size as outer, or empty
  bool down = false;
};
c4d::TriangleMesh closed_mesh(const Polygons& lower, const Polygons& upper, double gap, const DelaunayTiling& t,
                              const std::vector<Cap>& caps) {
  c4d::TriangleMesh m{positions(lower, upper, gap, t), t.triangles};
  for (const Cap& cap : caps) {
    std::vector<Triangle> tris;
    const std::size_t n = cap.outer.size();
    if (cap.hole.empty()) {
      for (std::size_t i = 1; i + 1 < n; ++i) tris.push_back({cap.outer[0], cap.outer[i], cap.outer[i + 1]});
    } else {
      auto h = [&](std::size_t i) { return cap.hole[(2 * n - 1 - i) % n]; };  // counter-clockwise hole
      for (std::size_t i = 0; i < n; ++i) {
        tris.push_back({cap.outer[i], cap.outer[(i + 1) % n], h((i + 1) % n)});
        tris.push_back({cap.outer[i], h((i + 1) % n), h(i)});
      }
    }
    for (Triangle tri : tris) {
      if (cap.down) std::swap(tri[1], tri[2]);
      m.triangles.push_back(tri);
    }
  }
  return m;
}

// Simple caps: one fan per polygon.
std::vector<Cap> fan_caps(const Polygons& lower, const Polygons& upper) {
  std::vector<Cap> caps;
  const auto ids = polygon_ids(lower, upper);
  for (std::size_t p = 0; p < ids.size(); ++p) caps.push_back({ids[p], {}, p < lower.size()});
  return caps;
}

void expect_closed(const c4d::TriangleMesh& mesh, long euler) {
  const c4d::TopologyReport check = c4d::check_topology(mesh);
  EXPECT_TRUE(check.closed_manifold()) << "boundary " << check.boundary_edges << ", non-manifold "
                                       << check.nonmanifold_edges << ", misoriented " << check.misoriented_edges
                                       << ", non-manifold vertices " << check.nonmanifold_vertices;
  EXPECT_EQ(check.degenerate_triangles, 0u);
  EXPECT_EQ(check.self_intersections, 0u);
  EXPECT_EQ(check.components.size(), 1u);
  EXPECT_EQ(check.euler, euler);
  EXPECT_GT(check.signed_volume, 0.0);
}

// Fraction-of-grid estimate of the areas of A∩B and A∪B (nesting parity), for volume bounds.
std::pair<double, double> overlap_areas(const Polygons& lower, const Polygons& upper) {
  auto inside = [](const Polygons& polygons, Vec2 q) {
    bool in = false;
    for (const auto& p : polygons)
      for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
        if ((p[i].y > q.y) != (p[j].y > q.y) && q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
          in = !in;
    return in;
  };
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Polygons* side : {&lower, &upper})
    for (const auto& p : *side)
      for (Vec2 q : p) x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x), y1 = std::max(y1, q.y);
  const int n = 400;
  const double dx = (x1 - x0) / n, dy = (y1 - y0) / n;
  double both = 0.0, any = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec2 q{x0 + (i + 0.5) * dx, y0 + (j + 0.5) * dy};
      const bool a = inside(lower, q), b = inside(upper, q);
      both += a && b ? dx * dy : 0.0;
      any += a || b ? dx * dy : 0.0;
    }
  return {both, any};
}

// The solid lies between the overlap (full height) and the union (nothing outside it).
void expect_volume_between_overlap_and_union(const Polygons& lower, const Polygons& upper, double gap,
                                             const DelaunayTiling& t) {
  const auto [both, any] = overlap_areas(lower, upper);
  const double v = band_volume(lower, upper, gap, t);
  EXPECT_GT(v, 0.99 * gap * both);
  EXPECT_LT(v, 1.01 * gap * any);
}

// Contours that cross or touch in projection: a valid band whose volume lies between the prisms
// of the overlap and of the union, closed by fan caps into a sphere-like mesh.
DelaunayTiling expect_valid_crossing(const Polygons& lower, const Polygons& upper, double gap) {
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  expect_volume_between_overlap_and_union(lower, upper, gap, t);
  expect_closed(closed_mesh(lower, upper, gap, t, fan_caps(lower, upper)), 2);
  return t;
}

TEST(DelaunayTiling, ConcentricCirclesGiveTheFrustum) {
  const Polygons lower{circle(0, 0, 10, 64)}, upper{circle(0, 0, 8, 64)};
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  EXPECT_EQ(t.crossing_points, 0u);
  const double frustum = kPi * gap / 3.0 * (100.0 + 80.0 + 64.0);
  EXPECT_NEAR(band_volume(lower, upper, gap, t), frustum, 0.02 * frustum);
  const auto mesh = closed_mesh(lower, upper, gap, t, fan_caps(lower, upper));
  expect_closed(mesh, 2);
  EXPECT_NEAR(c4d::signed_volume(mesh), frustum, 0.02 * frustum);
}

TEST(DelaunayTiling, FlatTrianglesGetLiftingPoints) {
  // Near the tips of a long lower ellipse, three consecutive contour points form empty Delaunay
  // triangles: flat after lifting unless CAT points break them up.
  const Polygons lower{ellipse(0, 0, 14, 4, 0.0, 64)}, upper{circle(0, 0, 2.5, 16)};
  const double gap = 4.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  EXPECT_GT(t.points.size(), 0u);
  EXPECT_GE(t.cat_rounds, 1);
  expect_closed(closed_mesh(lower, upper, gap, t, fan_caps(lower, upper)), 2);
  const double v = band_volume(lower, upper, gap, t);
  EXPECT_GT(v, gap * signed_area(upper));
  EXPECT_LT(v, gap * signed_area(lower));

  c4d::DelaunayTilingOptions none;
  none.max_cat_rounds = 0;
  const DelaunayTiling flat = c4d::tile_slices_delaunay(lower, upper, gap, none);
  EXPECT_GT(flat.flat_triangles, 0u);
  EXPECT_TRUE(flat.points.empty());
  EXPECT_FALSE(flat.warnings.empty());
}

TEST(DelaunayTiling, OffsetCirclesCrossInProjection) {
  const Polygons lower{circle(0, 0, 10, 64)}, upper{circle(3, 0, 10, 64)};
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  EXPECT_EQ(t.crossing_points, 2u);
  // A sheared cylinder: same cross-section area at every height.
  const double cylinder = gap * signed_area(lower);
  EXPECT_NEAR(band_volume(lower, upper, gap, t), cylinder, 0.05 * cylinder);
  expect_volume_between_overlap_and_union(lower, upper, gap, t);
  expect_closed(closed_mesh(lower, upper, gap, t, fan_caps(lower, upper)), 2);
}

TEST(DelaunayTiling, RotatedEllipseCrossesCircleFourTimes) {
  const Polygons lower{ellipse(0.5, -0.3, 13, 7, 0.4, 80)}, upper{circle(0, 0, 9.5, 60)};
  const double gap = 6.0;
  const DelaunayTiling t = expect_valid_crossing(lower, upper, gap);
  EXPECT_EQ(t.crossing_points, 4u);
}

TEST(DelaunayTiling, OneEllipseAboveTwoCircles) {
  const Polygons lower{circle(-6, 0, 4, 32), circle(6, 0.5, 4, 32)}, upper{ellipse(0, 0, 14, 7, 0.0, 72)};
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  EXPECT_EQ(t.crossing_points, 0u);
  const double v = band_volume(lower, upper, gap, t);
  EXPECT_GT(v, gap * signed_area(lower));
  EXPECT_LT(v, gap * signed_area(upper));
  expect_closed(closed_mesh(lower, upper, gap, t, fan_caps(lower, upper)), 2);
}

TEST(DelaunayTiling, TwoCirclesAboveOneEllipse) {
  const Polygons lower{ellipse(0, 0, 14, 7, 0.0, 72)}, upper{circle(-6, 0, 4, 32), circle(6, 0.5, 4, 32)};
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  const double v = band_volume(lower, upper, gap, t);
  EXPECT_GT(v, gap * signed_area(upper));
  EXPECT_LT(v, gap * signed_area(lower));
  expect_closed(closed_mesh(lower, upper, gap, t, fan_caps(lower, upper)), 2);
}

TEST(DelaunayTiling, TwoCirclesCrossingOneEllipse) {
  // n→1 where each lower circle sticks out of the upper ellipse.
  const Polygons lower{circle(-9, 0, 4, 32), circle(9, 0.5, 4, 32)}, upper{ellipse(0, 0, 11, 5, 0.1, 72)};
  const double gap = 5.0;
  const DelaunayTiling t = expect_valid_crossing(lower, upper, gap);
  EXPECT_EQ(t.crossing_points, 4u);
}

TEST(DelaunayTiling, RingWithHoleOnBothSlices) {
  const int n = 48;
  const Polygons lower{circle(0, 0, 10, n), circle(0, 0, 4, n, true)};
  const Polygons upper{circle(0, 0, 9, n), circle(0, 0, 5, n, true)};
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  const double ring = kPi * gap / 3.0 * ((100.0 + 90.0 + 81.0) - (16.0 + 20.0 + 25.0));
  EXPECT_NEAR(band_volume(lower, upper, gap, t), ring, 0.03 * ring);
  const auto ids = polygon_ids(lower, upper);
  const auto mesh = closed_mesh(lower, upper, gap, t, {{ids[0], ids[1], true}, {ids[2], ids[3], false}});
  expect_closed(mesh, 0);  // a torus
  EXPECT_NEAR(c4d::signed_volume(mesh), ring, 0.03 * ring);
}

TEST(DelaunayTiling, RingsWithCrossingHoles) {
  const int n = 48;
  const Polygons lower{circle(0, 0, 10, n), circle(1.5, 0, 4, n, true)};
  const Polygons upper{circle(0.5, 0, 10, n), circle(-1, 0.5, 4.5, n, true)};
  const double gap = 3.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  EXPECT_EQ(t.crossing_points, 4u);
  expect_volume_between_overlap_and_union(lower, upper, gap, t);
}

TEST(DelaunayTiling, IdenticalContoursGiveAVerticalWall) {
  const Polygons lower{ellipse(1, 2, 10, 6, 0.3, 40)}, upper = lower;
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  EXPECT_EQ(t.crossing_points, 40u);
  EXPECT_EQ(t.triangles.size(), 4u * 40u);
  const double prism = gap * signed_area(lower);
  EXPECT_NEAR(band_volume(lower, upper, gap, t), prism, 1e-9 * prism);
  expect_closed(closed_mesh(lower, upper, gap, t, fan_caps(lower, upper)), 2);
}

TEST(DelaunayTiling, VertexOnEdgeAndOverlappingEdges) {
  // The upper square shares part of the bottom and top edges with the lower one, and two lower
  // vertices lie on upper edges.
  const Polygons lower{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}};
  const Polygons upper{{{5, 0}, {15, 0}, {15, 10}, {5, 10}}};
  const double gap = 4.0;
  expect_valid_crossing(lower, upper, gap);
}

TEST(DelaunayTiling, SharedVertexOnly) {
  // A square and a diamond that touch at one vertex and cross elsewhere.
  const Polygons lower{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}};
  const Polygons upper{{{10, 5}, {14, 9}, {10, 13}, {6, 9}}};
  const double gap = 2.0;
  expect_valid_crossing(lower, upper, gap);
}

TEST(DelaunayTiling, CoincidentVertex) {
  // The upper quadrilateral has one vertex on a corner of the lower square and crosses its boundary
  // three times (top, left, left).
  const Polygons lower{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}};
  const Polygons upper{{{10, 10}, {3, 14}, {-3, 5}, {4, 3}}};
  const double gap = 3.0;
  const DelaunayTiling t = expect_valid_crossing(lower, upper, gap);
  EXPECT_EQ(t.crossing_points, 4u);  // the shared corner and three crossings
}

TEST(DelaunayTiling, HoleAppearsOnUpperSlice) {
  // Identical outer contours; only the upper slice has a hole: the band dips into it.
  const int n = 40;
  const Polygons lower{circle(0, 0, 10, n)};
  const Polygons upper{circle(0, 0, 10, n), circle(0.5, 0, 4, n, true)};
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  expect_valid_band(lower, upper, gap, t);
  EXPECT_EQ(t.crossing_points, static_cast<std::size_t>(n));
  const double v = band_volume(lower, upper, gap, t);
  EXPECT_GT(v, gap * signed_area(upper));
  EXPECT_LT(v, gap * signed_area(lower));
  const auto ids = polygon_ids(lower, upper);
  expect_closed(closed_mesh(lower, upper, gap, t, {{ids[0], {}, true}, {ids[1], ids[2], false}}), 2);
}

TEST(DelaunayTiling, DeterministicOutput) {
  const Polygons lower{ellipse(0.5, -0.3, 13, 7, 0.4, 80)}, upper{circle(0, 0, 9.5, 60)};
  const DelaunayTiling a = c4d::tile_slices_delaunay(lower, upper, 6.0);
  const DelaunayTiling b = c4d::tile_slices_delaunay(lower, upper, 6.0);
  EXPECT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) EXPECT_TRUE(a.points[i] == b.points[i]);
}

TEST(DelaunayTiling, InvariantToRigidMotionAndStartPoint) {
  const Polygons lower{circle(-6, 0, 4, 32), circle(6, 0.5, 4, 32)}, upper{ellipse(0, 0, 14, 7, 0.2, 72)};
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(lower, upper, gap);
  const double v = band_volume(lower, upper, gap, t);
  // A quarter turn and an integer shift are exact in floating point.
  auto move = [](Polygons ps) {
    for (auto& p : ps)
      for (Vec2& q : p) q = {-q.y + 100.0, q.x - 40.0};
    return ps;
  };
  const Polygons lm = move(lower), um = move(upper);
  const DelaunayTiling tm = c4d::tile_slices_delaunay(lm, um, gap);
  expect_valid_band(lm, um, gap, tm);
  EXPECT_NEAR(band_volume(lm, um, gap, tm), v, 1e-6 * v);
  // Start points shifted.
  Polygons ls = lower, us = upper;
  std::rotate(ls[0].begin(), ls[0].begin() + 5, ls[0].end());
  std::rotate(us[0].begin(), us[0].begin() + 11, us[0].end());
  const DelaunayTiling ts = c4d::tile_slices_delaunay(ls, us, gap);
  expect_valid_band(ls, us, gap, ts);
  EXPECT_NEAR(band_volume(ls, us, gap, ts), v, 1e-6 * v);
}

TEST(DelaunayTiling, WrongOrientationIsFollowedByNesting) {
  const Polygons lower{circle(0, 0, 10, 64)}, upper{circle(3, 0, 10, 64)};
  Polygons reversed_lower = lower;
  std::reverse(reversed_lower[0].begin(), reversed_lower[0].end());
  const double gap = 5.0;
  const DelaunayTiling t = c4d::tile_slices_delaunay(reversed_lower, upper, gap);
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_NE(t.warnings[0].find("convention"), std::string::npos);
  EXPECT_NEAR(band_volume(reversed_lower, upper, gap, t), gap * signed_area(lower), 0.05 * gap * signed_area(lower));
}

TEST(DelaunayTiling, BadInputThrows) {
  const Polygons ok{circle(0, 0, 5, 8)};
  EXPECT_THROW(c4d::tile_slices_delaunay({}, ok, 1.0), c4d::InvalidInput);
  EXPECT_THROW(c4d::tile_slices_delaunay(ok, {}, 1.0), c4d::InvalidInput);
  EXPECT_THROW(c4d::tile_slices_delaunay({{{0, 0}, {1, 0}}}, ok, 1.0), c4d::InvalidInput);
  EXPECT_THROW(c4d::tile_slices_delaunay(ok, ok, 0.0), c4d::InvalidInput);
  EXPECT_THROW(c4d::tile_slices_delaunay(ok, ok, -2.0), c4d::InvalidInput);
  EXPECT_THROW(c4d::tile_slices_delaunay(ok, ok, std::nan("")), c4d::InvalidInput);
  EXPECT_THROW(c4d::tile_slices_delaunay({{{0, 0}, {1, 0}, {std::nan(""), 1}}}, ok, 1.0), c4d::InvalidInput);
  // Repeated point, crossing polygons of one slice.
  EXPECT_THROW(c4d::tile_slices_delaunay({{{0, 0}, {4, 0}, {4, 0}, {0, 4}}}, ok, 1.0), c4d::InvalidInput);
  EXPECT_THROW(c4d::tile_slices_delaunay({{{0, 0}, {4, 4}, {4, 0}, {0, 4}}}, ok, 1.0), c4d::InvalidInput);
  EXPECT_THROW(c4d::tile_slices_delaunay({circle(0, 0, 5, 8), circle(3, 0, 5, 8)}, ok, 1.0), c4d::InvalidInput);
  try {
    c4d::tile_slices_delaunay(ok, {{{0, 0}, {1, 0}}}, 1.0);
    ADD_FAILURE() << "no throw";
  } catch (const c4d::InvalidInput& e) {
    EXPECT_EQ(e.code(), c4d::ErrorCode::DegenerateContour);
    EXPECT_NE(std::string(e.what()).find("upper polygon 0"), std::string::npos) << e.what();
  }
}

}  // namespace
