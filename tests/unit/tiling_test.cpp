// Tiling between two contours, bridges, resampling and caps: combinatorial properties.
#include "contour4d/surface/tiling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "contour4d/core/contour.h"
#include "contour4d/core/errors.h"
#include "contour4d/surface/capping.h"
#include "contour4d/surface/refine.h"
#include "contour4d/surface/resample.h"

namespace {

using c4d::Vec2;
using c4d::Vec3;

std::vector<Vec2> ellipse(double a, double b, int n, double phase = 0.0) {
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double t = phase + 2.0 * M_PI * i / n;
    p.push_back({a * std::cos(t), b * std::sin(t)});
  }
  return p;
}

// Directed edge use counts.
std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed(const std::vector<c4d::Triangle>& t) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> m;
  for (const auto& f : t)
    for (int k = 0; k < 3; ++k) ++m[{f[k], f[(k + 1) % 3]}];
  return m;
}

TEST(Tiling, BandUsesEveryChainEdgeOnceAndFacesOutward) {
  std::vector<Vec3> pos;
  std::vector<std::uint32_t> lo, up;
  for (const Vec2& p : ellipse(10, 6, 23)) {
    lo.push_back(static_cast<std::uint32_t>(pos.size()));
    pos.push_back({p.x, p.y, 0});
  }
  for (const Vec2& p : ellipse(8, 7, 31, 0.3)) {
    up.push_back(static_cast<std::uint32_t>(pos.size()));
    pos.push_back({p.x, p.y, 5});
  }
  const auto tris = c4d::tile_chains(lo, up, pos);
  EXPECT_EQ(tris.size(), lo.size() + up.size());
  const auto use = directed(tris);
  for (std::size_t k = 0; k < lo.size(); ++k) EXPECT_EQ(use.at({lo[k], lo[(k + 1) % lo.size()]}), 1);
  for (std::size_t k = 0; k < up.size(); ++k) EXPECT_EQ(use.at({up[(k + 1) % up.size()], up[k]}), 1);
  for (const auto& [e, n] : use) EXPECT_EQ(n, 1);
  for (const auto& f : tris) {
    // No flat triangle: both slices appear.
    const bool has_lo = f[0] < lo.size() || f[1] < lo.size() || f[2] < lo.size();
    const bool has_up = f[0] >= lo.size() || f[1] >= lo.size() || f[2] >= lo.size();
    EXPECT_TRUE(has_lo && has_up);
    // Outward: the normal points away from the axis.
    const Vec3 a = pos[f[0]], b = pos[f[1]], c = pos[f[2]];
    const Vec3 n = c4d::cross(b - a, c - a), centre = (a + b + c) / 3.0;
    EXPECT_GT(n.x * centre.x + n.y * centre.y, 0.0);
  }
}

// The band's dynamic programme leaves out states that cannot be on an optimal path (tiling.cpp): on
// rows a row apart (the corridor is narrow), shifted sideways (an oblique stack), with very different
// point counts, and on chains that interleave in height (no separation to prune with), the band's
// total spanning-edge length equals the optimum of the full programme from the same start
// (lower[0] and its nearest upper point), worked out here independently.
TEST(Tiling, BandIsTheOptimumOfTheFullProgramme) {
  struct Case {
    int n, m;
    double r_lo, r_up, dz, shift, wobble;
  };
  const Case cases[] = {{150, 130, 10.0, 10.5, 1.0, 0.0, 0.05},
                        {120, 120, 10.0, 9.0, 1.0, 3.0, 0.1},
                        {40, 200, 6.0, 12.0, 5.0, 0.0, 0.0},
                        {90, 70, 8.0, 8.2, 0.3, 0.5, 0.8}};
  for (const Case& c : cases) {
    std::vector<Vec3> pos;
    std::vector<std::uint32_t> lo, up;
    for (int i = 0; i < c.n; ++i) {
      const double t = 2.0 * M_PI * i / c.n;
      lo.push_back(static_cast<std::uint32_t>(pos.size()));
      pos.push_back({c.r_lo * std::cos(t), c.r_lo * std::sin(t), c.wobble * std::sin(7.0 * t)});
    }
    for (int j = 0; j < c.m; ++j) {
      const double t = 0.1 + 2.0 * M_PI * j / c.m;
      up.push_back(static_cast<std::uint32_t>(pos.size()));
      pos.push_back({c.shift + c.r_up * std::cos(t), c.r_up * std::sin(t), c.dz + c.wobble * std::cos(5.0 * t)});
    }
    // The tiling's spanning edges (one per state of its path; the closing one is the starting one).
    std::set<std::pair<std::uint32_t, std::uint32_t>> spanning;
    for (const auto& f : c4d::tile_chains(lo, up, pos))
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = f[k], b = f[(k + 1) % 3];
        if ((a < lo.size()) != (b < lo.size())) spanning.insert({std::min(a, b), std::max(a, b)});
      }
    double ours = 0.0;
    for (const auto& [a, b] : spanning) ours += c4d::distance(pos[a], pos[b]);
    // The full programme.
    std::size_t j0 = 0;
    for (std::size_t j = 1; j < up.size(); ++j)
      if (c4d::distance(pos[lo[0]], pos[up[j]]) < c4d::distance(pos[lo[0]], pos[up[j0]])) j0 = j;
    const std::size_t n = lo.size(), m = up.size();
    auto d = [&](std::size_t i, std::size_t j) { return c4d::distance(pos[lo[i % n]], pos[up[(j0 + j) % m]]); };
    std::vector<double> best((n + 1) * (m + 1), std::numeric_limits<double>::infinity());
    best[0] = 0.0;
    for (std::size_t i = 0; i <= n; ++i)
      for (std::size_t j = 0; j <= m; ++j) {
        if (i > 0) best[i * (m + 1) + j] = std::min(best[i * (m + 1) + j], best[(i - 1) * (m + 1) + j] + d(i, j));
        if (j > 0) best[i * (m + 1) + j] = std::min(best[i * (m + 1) + j], best[i * (m + 1) + j - 1] + d(i, j));
      }
    const double optimum = best[n * (m + 1) + m];
    EXPECT_EQ(spanning.size(), n + m);
    EXPECT_NEAR(ours, optimum, 1e-9 * optimum) << c.n << " x " << c.m;
  }
}

TEST(Tiling, BridgeWalksThereAndBack) {
  const std::vector<std::uint32_t> a{0, 1, 2, 3}, b{10, 11, 12}, br{20, 21};
  const auto m = c4d::bridge_chains(a, 1, b, 2, br);
  EXPECT_EQ(m, (std::vector<std::uint32_t>{0, 1, 20, 21, 12, 10, 11, 12, 21, 20, 1, 2, 3}));
}

TEST(Resample, EvenSpacingAndSamePointsWhicheverWayTheContourRuns) {
  const auto e = c4d::canonical_polygon(ellipse(20, 11, 57), true);
  c4d::ResampleOptions o;
  o.edge = 1.0;
  const auto r = c4d::resample_closed(e, o);
  for (std::size_t k = 0; k < r.size(); ++k) EXPECT_LE(c4d::norm(r[(k + 1) % r.size()] - r[k]), 1.0 + 1e-9);
  auto rev = e;
  std::reverse(rev.begin(), rev.end());
  std::rotate(rev.begin(), rev.begin() + 7, rev.end());
  const auto rc = c4d::resample_closed(c4d::canonical_polygon(rev, true), o);
  ASSERT_EQ(rc.size(), r.size());
  for (std::size_t k = 0; k < r.size(); ++k) EXPECT_NEAR(c4d::norm(rc[k] - r[k]), 0.0, 1e-9);
}

TEST(Resample, CornersAreKept) {
  const std::vector<Vec2> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const auto r = c4d::resample_closed(square, {1.5, 30.0});
  for (const Vec2& c : square) EXPECT_NE(std::find(r.begin(), r.end(), c), r.end());
  EXPECT_EQ(r.size(), 28u);  // 4 sides of 10 mm in 7 pieces
}

TEST(Resample, ATightBendIsNotAChainOfCorners) {
  // A peanut-like section: two circles of radius 8 joined by a dimple of radius 1 mm, sampled every
  // 0.05 mm. Every vertex of the dimple turns more than 30° at the scale of one edge; only the
  // sharpest may be kept, so pieces stay a good part of an edge long.
  std::vector<Vec2> p;
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < 2000; ++k) {
    const double t = 2 * pi * k / 2000;
    const double r = 8.0 - 5.0 * std::exp(-std::pow(std::sin(t) / 0.12, 2));  // dimples at t = 0, π
    p.push_back({r * std::cos(t) * 1.6, r * std::sin(t)});
  }
  c4d::ResampleOptions o;
  o.edge = 1.25;
  const auto r = c4d::resample_closed(c4d::canonical_polygon(p, true), o);
  double shortest = 1e9;
  for (std::size_t k = 0; k < r.size(); ++k) shortest = std::min(shortest, c4d::norm(r[(k + 1) % r.size()] - r[k]));
  EXPECT_GT(shortest, 0.2 * o.edge) << r.size() << " points";  // every input vertex kept: 0.05 mm
}

TEST(Resample, NeedlesAreRemoved) {
  // A square with a one-pixel needle out of its top side and back along the same line.
  const std::vector<Vec2> spiky{{0, 0}, {10, 0}, {10, 10}, {5, 10}, {5, 12}, {5, 10}, {0, 10}};
  const auto r = c4d::resample_closed(spiky, {1.0, 30.0});
  for (const Vec2& q : r) EXPECT_LE(q.y, 10.0 + 1e-12);
  EXPECT_NEAR(std::abs(c4d::signed_area(r)), 100.0, 1e-9);
}

TEST(Refine, FlipsRemoveAFlatTriangleAndKeepContourEdges) {
  // A fan cap whose first triangle has three collinear contour vertices (0, 1, 2); the loop
  // 0-1-2-3-4 is the contour (constrained).
  c4d::TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  const std::vector<std::array<std::uint32_t, 2>> contour{{0, 1}, {1, 2}, {2, 3}, {3, 4}, {0, 4}};
  EXPECT_GE(c4d::flip_edges_delaunay(m, contour), 1u);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles) {
    const Vec3 n = c4d::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    EXPECT_GT(n.z, 1e-9) << "flat or flipped triangle";
    for (int k = 0; k < 3; ++k) ++edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  }
  for (const auto& e : contour) EXPECT_EQ(edges[std::make_pair(e[0], e[1])], 1) << e[0] << "-" << e[1];
}

TEST(Refine, EarsAreFlippedSoThatAStraightenedContourLeavesNoFlatTriangle) {
  // A cap on a closed contour of 2k vertices whose every other vertex is an ear's middle (three contour
  // vertices in one triangle). A mesh laid onto another frame where the contour is straight there (the middle
  // vertex on its chord) must have no flat triangle: flip_ears makes each middle vertex join the inside.
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    std::uint64_t state = seed * 7919;
    auto next = [&state] {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(state >> 11) / 9007199254740992.0;  // [0, 1)
    };
    const std::uint32_t k = 5 + static_cast<std::uint32_t>(seed % 4), n = 2 * k;
    c4d::TriangleMesh m;
    const double pi = 3.14159265358979323846;
    for (std::uint32_t i = 0; i < n; ++i) {  // contour vertices 0 .. n-1, counter-clockwise
      const double a = 2 * pi * (i + 0.2 * (next() - 0.5)) / n, r = 10 + next();
      m.positions.push_back({r * std::cos(a), r * std::sin(a), 0});
    }
    for (std::uint32_t i = 0; i < k; ++i) {  // inner vertices n .. n+k-1, beside each ear's middle
      const double a = 2 * pi * (2 * i + 1) / n;
      m.positions.push_back({6 * std::cos(a), 6 * std::sin(a), 0.3 * next()});
    }
    m.positions.push_back({0, 0, 0.5});  // the centre, n + k
    std::vector<std::array<std::uint32_t, 2>> contour;
    for (std::uint32_t i = 0; i < n; ++i) contour.push_back({i, (i + 1) % n});
    for (std::uint32_t i = 0; i < k; ++i) {
      const std::uint32_t b0 = 2 * i, b1 = 2 * i + 1, b2 = (2 * i + 2) % n, in = n + i, in2 = n + (i + 1) % k;
      m.triangles.push_back({b0, b1, b2});  // the ear
      m.triangles.push_back({b0, b2, in});
      m.triangles.push_back({in, b2, in2});
      m.triangles.push_back({n + k, in, in2});
    }
    EXPECT_EQ(c4d::flip_ears(m, contour), k) << "seed " << seed;
    c4d::TriangleMesh straight = m;  // each ear's middle on its chord
    for (std::uint32_t i = 0; i < k; ++i)
      straight.positions[2 * i + 1] = 0.5 * (m.positions[2 * i] + m.positions[(2 * i + 2) % n]);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (const auto& t : straight.triangles) {
      const Vec3 nrm = c4d::cross(straight.positions[t[1]] - straight.positions[t[0]],
                                  straight.positions[t[2]] - straight.positions[t[0]]);
      EXPECT_GT(c4d::norm(nrm), 1e-3) << "flat triangle, seed " << seed;
      EXPECT_GT(nrm.z, 0.0) << "flipped triangle, seed " << seed;
      for (int j = 0; j < 3; ++j) ++edges[{std::min(t[j], t[(j + 1) % 3]), std::max(t[j], t[(j + 1) % 3])}];
    }
    for (const auto& e : contour)
      EXPECT_EQ(edges[std::make_pair(std::min(e[0], e[1]), std::max(e[0], e[1]))], 1) << "seed " << seed;
    EXPECT_EQ(c4d::flip_ears(m, contour), 0u) << "no ear is left, seed " << seed;
  }
}

TEST(Refine, FlipsSkippingAcuteEdgesAreThoseOfTestingEveryEdge) {
  // A jittered, sheared grid on a gently bent sheet, each cell split along a random diagonal: many edges fail
  // the Delaunay test and flips cascade over several rounds. Skipping the edges beside two acute
  // angles must give the same triangles, flip for flip, as testing every edge.
  constexpr std::uint32_t kSide = 40;
  c4d::TriangleMesh m;
  std::uint64_t state = 12345;
  auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;  // [0, 1)
  };
  for (std::uint32_t j = 0; j < kSide; ++j)
    for (std::uint32_t i = 0; i < kSide; ++i) {
      // Sheared rows: the Delaunay edges span several grid cells, so flips cascade.
      const double x = i + 0.9 * j + 0.2 * (next() - 0.5), y = 0.3 * j + 0.06 * (next() - 0.5);
      m.positions.push_back({x, y, 0.01 * x * x});
    }
  auto at = [](std::uint32_t i, std::uint32_t j) { return j * kSide + i; };
  for (std::uint32_t j = 0; j + 1 < kSide; ++j)
    for (std::uint32_t i = 0; i + 1 < kSide; ++i) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (next() < 0.5) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      }
    }
  const std::vector<std::array<std::uint32_t, 2>> contour{{at(0, 0), at(1, 0)}, {at(1, 0), at(2, 0)}};
  // One round as well: a round's result depends on the flips earlier in it (the full run converges
  // to the same triangles whatever the order).
  for (const auto& [below, rounds] : {std::pair{0.0, 20}, std::pair{35.0, 20}, std::pair{0.0, 1}, std::pair{35.0, 1}}) {
    c4d::FlipOptions every, skipping;
    every.only_below_deg = skipping.only_below_deg = below;
    every.max_rounds = skipping.max_rounds = rounds;
    every.skip_acute = false;
    c4d::TriangleMesh a = m, b = m;
    const std::size_t flips_every = c4d::flip_edges_delaunay(a, contour, every);
    const std::size_t flips_skipping = c4d::flip_edges_delaunay(b, contour, skipping);
    EXPECT_GT(flips_every, 100u) << below << " " << rounds;
    EXPECT_EQ(flips_every, flips_skipping) << below << " " << rounds;
    EXPECT_EQ(a.triangles, b.triangles) << below << " " << rounds;
  }
}

TEST(Capping, CapCoversTheRegionAndKeepsLoopEdges) {
  const auto outer = c4d::canonical_polygon(ellipse(15, 9, 60), true);
  const auto hole = c4d::canonical_polygon(ellipse(4, 3, 20), false);
  for (c4d::CapStyle style : {c4d::CapStyle::Flat, c4d::CapStyle::Rounded}) {
    const auto cap = c4d::triangulate_cap({outer, hole}, style, {1.5, 2.0});
    double area = 0.0;
    for (const auto& t : cap.triangles) {
      const double a = 0.5 * c4d::cross(cap.points[t[1]] - cap.points[t[0]], cap.points[t[2]] - cap.points[t[0]]);
      EXPECT_GT(a, 0.0);
      area += a;
    }
    EXPECT_NEAR(area, c4d::signed_area(outer) + c4d::signed_area(hole), 1e-6);
    const auto use = directed(cap.triangles);
    for (std::size_t k = 0; k < outer.size(); ++k)
      EXPECT_EQ(use.count({static_cast<std::uint32_t>(k), static_cast<std::uint32_t>((k + 1) % outer.size())}), 1u);
    const double hmax = *std::max_element(cap.height.begin(), cap.height.end());
    if (style == c4d::CapStyle::Flat)
      EXPECT_EQ(hmax, 0.0);
    else
      EXPECT_NEAR(hmax, 2.0, 0.3);
    EXPECT_GT(cap.points.size(), outer.size() + hole.size());
  }
}

// A Rounded dome's height is a circular profile of each interior point's distance to the nearest loop
// segment (triangulate_cap finds it through a grid of segment cells): the same as scanning every
// segment, to the bit, on a ring with a hole near one side and segments of very different lengths.
TEST(Capping, DomeHeightsFollowTheExactDistanceToTheLoops) {
  std::vector<Vec2> outer = ellipse(30, 12, 90);
  outer.insert(outer.begin() + 10,
               Vec2{(outer[9].x + outer[10].x) / 2, (outer[9].y + outer[10].y) / 2});  // a short segment
  const auto o = c4d::canonical_polygon(outer, true);
  std::vector<Vec2> hole = ellipse(3, 2, 12);
  for (Vec2& p : hole) p.x += 20;
  const auto h = c4d::canonical_polygon(hole, false);
  const auto cap = c4d::triangulate_cap({o, h}, c4d::CapStyle::Rounded, {1.0, 2.0});
  const std::size_t loop_points = o.size() + h.size();
  ASSERT_GT(cap.points.size(), loop_points + 100);
  std::vector<double> d(cap.points.size(), 0.0);
  double dmax = 0.0;
  for (std::size_t i = loop_points; i < cap.points.size(); ++i) {
    d[i] = std::numeric_limits<double>::infinity();
    for (const auto* loop : {&o, &h})
      for (std::size_t k = 0; k < loop->size(); ++k)
        d[i] = std::min(d[i], c4d::segment_distance(cap.points[i], (*loop)[k], (*loop)[(k + 1) % loop->size()]));
    dmax = std::max(dmax, d[i]);
    EXPECT_GE(d[i], 0.4) << "interior point " << i << " within 0.4 edge of a loop";
  }
  const double top = std::min(2.0, dmax);
  for (std::size_t i = loop_points; i < cap.points.size(); ++i) {
    const double t = std::min(1.0, d[i] / dmax);
    EXPECT_EQ(cap.height[i], top * std::sqrt(std::max(0.0, 1.0 - (1.0 - t) * (1.0 - t)))) << "point " << i;
  }
}

// CapOptions::uniform_scale: CGAL's size bound caps each triangle's longest edge, so a uniform interior
// at bound `edge` has a mean edge near 0.7 edge; at √2 edges the mean is near `edge`, with about half the
// points.
TEST(Capping, UniformScaleGivesAMeanEdgeNearTheEdgeLength) {
  const auto outer = c4d::canonical_polygon(ellipse(25, 20, 140), true);
  const auto hole = c4d::canonical_polygon(ellipse(10, 8, 56), false);
  auto mean_interior_edge = [&](const c4d::CapMesh& cap) {
    const std::size_t loop_points = outer.size() + hole.size();
    double sum = 0.0;
    std::size_t n = 0;
    for (const auto& t : cap.triangles)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
        if (a < loop_points || b < loop_points) continue;
        sum += c4d::norm(cap.points[a] - cap.points[b]);
        ++n;
      }
    return n > 0 ? sum / static_cast<double>(n) : 0.0;
  };
  c4d::CapOptions plain{1.0, 2.0}, scaled{1.0, 2.0};
  plain.far_scale = scaled.far_scale = 1.0;
  ASSERT_EQ(plain.uniform_scale, 1.0);
  scaled.uniform_scale = std::sqrt(2.0);
  const auto p = c4d::triangulate_cap({outer, hole}, c4d::CapStyle::Rounded, plain);
  const auto s = c4d::triangulate_cap({outer, hole}, c4d::CapStyle::Rounded, scaled);
  EXPECT_LT(mean_interior_edge(p), 0.8);
  EXPECT_GT(mean_interior_edge(s), 0.85);
  EXPECT_LT(mean_interior_edge(s), 1.15);
  EXPECT_LT(s.points.size(), 0.65 * static_cast<double>(p.points.size()));
  double area = 0.0;
  for (const auto& t : s.triangles)
    area += 0.5 * c4d::cross(s.points[t[1]] - s.points[t[0]], s.points[t[2]] - s.points[t[0]]);
  EXPECT_NEAR(area, c4d::signed_area(outer) + c4d::signed_area(hole), 1e-6);
  // Below 1 (or NaN) it is 1: the bound never falls below `edge`.
  for (double u : {0.5, std::numeric_limits<double>::quiet_NaN()}) {
    c4d::CapOptions o = plain;
    o.uniform_scale = u;
    EXPECT_EQ(c4d::triangulate_cap({outer, hole}, c4d::CapStyle::Rounded, o).points, p.points) << u;
  }
}

// CapOptions::far_scale: next to the loops the interior points are as dense as with a uniform bound
// (the fairing's smoothness across the contour depends on them); far from them, fewer.
TEST(Capping, InteriorCoarsensAwayFromTheLoops) {
  const auto loop = c4d::canonical_polygon(ellipse(25, 20, 140), true);
  c4d::CapOptions uniform{1.0, 2.0};
  uniform.far_scale = 1.0;
  const c4d::CapOptions graded{1.0, 2.0};  // the defaults: near 2 edges, ramp to 5, far 3
  ASSERT_EQ(graded.near_edges, 2.0);
  ASSERT_EQ(graded.ramp_edges, 5.0);
  ASSERT_EQ(graded.far_scale, 3.0);
  auto count = [&](const c4d::CapMesh& cap, double lo, double hi) {
    std::size_t n = 0;
    for (std::size_t i = loop.size(); i < cap.points.size(); ++i) {
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < loop.size(); ++k)
        d = std::min(d, c4d::segment_distance(cap.points[i], loop[k], loop[(k + 1) % loop.size()]));
      EXPECT_GE(d, 0.4) << "interior point " << i << " within 0.4 edge of the loop";
      if (d >= lo && d < hi) ++n;
    }
    return n;
  };
  for (c4d::CapStyle style : {c4d::CapStyle::Flat, c4d::CapStyle::Rounded}) {
    const auto u = c4d::triangulate_cap({loop}, style, uniform), g = c4d::triangulate_cap({loop}, style, graded);
    const double near_u = static_cast<double>(count(u, 0.0, 1.5)), near_g = static_cast<double>(count(g, 0.0, 1.5));
    EXPECT_GT(near_g, 0.85 * near_u);
    EXPECT_LT(near_g, 1.15 * near_u);
    const double far_u = static_cast<double>(count(u, 6.0, 1e9)), far_g = static_cast<double>(count(g, 6.0, 1e9));
    EXPECT_GT(far_u, 500.0);
    EXPECT_LT(far_g, 0.3 * far_u);  // about (1/3)² of the points where the bound is 3 edges
    EXPECT_LT(g.points.size(), u.points.size() / 2);
    // Still a triangulation of the whole region.
    double area = 0.0;
    for (const auto& t : g.triangles)
      area += 0.5 * c4d::cross(g.points[t[1]] - g.points[t[0]], g.points[t[2]] - g.points[t[0]]);
    EXPECT_NEAR(area, c4d::signed_area(loop), 1e-6);
    // A far bound of 0, below 1 or NaN is the uniform one (0 or NaN as a bound would never stop refining).
    for (double far : {0.0, 0.5, std::numeric_limits<double>::quiet_NaN()}) {
      c4d::CapOptions o{1.0, 2.0};
      o.far_scale = far;
      const auto w = c4d::triangulate_cap({loop}, style, o);
      EXPECT_EQ(w.points, u.points) << "far_scale " << far;
    }
  }
}

TEST(Caps, ExtrapolatedVolumeFollowsTheLastTwoSections) {
  // A tube cut across: the full prism, up to max_fill.
  EXPECT_DOUBLE_EQ(c4d::extrapolated_cap_volume(100, 100, 5, 2.5, 1.0), 250.0);
  EXPECT_DOUBLE_EQ(c4d::extrapolated_cap_volume(100, 100, 5, 2.5, 0.95), 237.5);
  // Slowly shrinking: ∫₀^2.5 (100 − d) dd.
  EXPECT_DOUBLE_EQ(c4d::extrapolated_cap_volume(100, 105, 5, 2.5, 1.0), 250.0 - 0.5 * 2.5 * 2.5);
  // Growing sections never give more than the prism (the cap stays over its contour).
  EXPECT_DOUBLE_EQ(c4d::extrapolated_cap_volume(100, 50, 5, 2.5, 1.0), 250.0);
  // A closing end: the area reaches 0 at d = 40 / 12 past it.
  EXPECT_NEAR(c4d::extrapolated_cap_volume(40, 100, 5, 2.5, 1.0), 40 * 2.5 - 0.5 * 12 * 2.5 * 2.5, 1e-12);
  EXPECT_NEAR(c4d::extrapolated_cap_volume(20, 100, 5, 2.5, 1.0), 0.5 * 20 * 20 / 16.0, 1e-12);
  EXPECT_EQ(c4d::extrapolated_cap_volume(0, 0, 5, 2.5, 1.0), 0.0);
}

TEST(Caps, HermiteBandVolumeIsExactForCubicAreas) {
  EXPECT_DOUBLE_EQ(c4d::hermite_band_volume(7, 7, 0, 0, 3), 21.0);  // constant area
  EXPECT_DOUBLE_EQ(c4d::hermite_band_volume(2, 8, 2, 2, 3), 15.0);  // linear area: the trapezoid
  // A(t) = t³ on [0, 2]: ∫ = 4.
  EXPECT_NEAR(c4d::hermite_band_volume(0, 8, 0, 12, 2), 4.0, 1e-12);
}

TEST(Caps, FillLiftsADomeToItsTargetWithoutMovingTheRim) {
  const auto loop = ellipse(10, 10, 64);
  const auto cap = c4d::triangulate_cap({loop}, c4d::CapStyle::Rounded, {1.0, 2.5});
  std::vector<Vec3> pos;
  for (std::size_t k = 0; k < cap.points.size(); ++k)
    pos.push_back({cap.points[k].x, cap.points[k].y, 3.0 - cap.height[k]});
  const c4d::CapFrame frame{3.0, -1.0, 2.5};  // a bottom cap under the plane z = 3
  const double area = c4d::signed_area(loop);
  const double before = c4d::cap_volume(pos, cap.triangles, frame);
  EXPECT_NEAR(before, 2.0 / 3.0 * area * 2.5, 0.05 * area * 2.5);  // a half ellipsoid
  // Already full enough: unchanged.
  auto same = pos;
  EXPECT_EQ(c4d::fill_cap(same, cap.triangles, frame, 0.5 * area * 2.5), 0.0);
  EXPECT_EQ(same, pos);
  const double target = 0.9 * area * 2.5;
  auto filled = pos;
  const double c = c4d::fill_cap(filled, cap.triangles, frame, target);
  EXPECT_GT(c, 0.0);
  EXPECT_NEAR(c4d::cap_volume(filled, cap.triangles, frame), target, 1e-6 * target);
  for (std::size_t k = 0; k < pos.size(); ++k) {
    EXPECT_EQ(filled[k].x, pos[k].x);
    EXPECT_EQ(filled[k].y, pos[k].y);
    EXPECT_LE(filled[k].z, pos[k].z);  // only lifted (downwards here)
    // The lift is second order in the height over the plane: the cap leaves its rim with the slope it had.
    const double u = 3.0 - pos[k].z;
    EXPECT_NEAR(pos[k].z - filled[k].z, c * u * u / 2.5, 1e-9);
    if (k < loop.size()) {
      EXPECT_EQ(filled[k].z, 3.0);
    }
  }
}

TEST(Caps, EndBandWidensToItsTarget) {
  // A cone-like wall from a circle of radius 10 (z = 0) up to radius 2 (z = 5), as fairing leaves
  // between a large contour and a small end contour.
  const int n = 48, rings = 10;
  std::vector<Vec3> pos;
  std::vector<c4d::Triangle> tris;
  for (int k = 0; k <= rings; ++k) {
    const double r = 10.0 - 8.0 * k / rings, z = 5.0 * k / rings;
    for (const Vec2& p : ellipse(r, r, n)) pos.push_back({p.x + 1.0, p.y - 2.0, z});
  }
  auto id = [&](int k, int i) { return static_cast<std::uint32_t>(k * n + (i % n)); };
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < n; ++i) {
      tris.push_back({id(k, i), id(k, i + 1), id(k + 1, i + 1)});
      tris.push_back({id(k, i), id(k + 1, i + 1), id(k + 1, i)});
    }
  c4d::EndBand band;
  band.triangles = tris;
  for (int v = n; v < rings * n; ++v) band.movable.push_back(static_cast<std::uint32_t>(v));
  band.z_end = 5.0;
  band.z_ref = 0.0;
  band.c_end = band.c_ref = {1.0, -2.0};
  const double polygon = 0.5 * n * std::sin(2 * M_PI / n);  // area of the unit 48-gon
  band.area_end = 4.0 * polygon;
  const double before = c4d::end_band_volume(pos, band);
  EXPECT_NEAR(before, polygon * 5.0 / 3.0 * (100 + 20 + 4), 1e-9 * before);  // the frustum
  auto same = pos;
  EXPECT_EQ(c4d::fill_end_band(same, band, 0.9 * before), 0.0);
  EXPECT_EQ(same, pos);
  const double target = 1.15 * before;
  auto wide = pos;
  const double alpha = c4d::fill_end_band(wide, band, target);
  EXPECT_GT(alpha, 0.0);
  EXPECT_LT(alpha, 0.5);
  EXPECT_NEAR(c4d::end_band_volume(wide, band), target, 1e-6 * target);
  for (int v = 0; v < static_cast<int>(pos.size()); ++v) {
    EXPECT_EQ(wide[static_cast<std::size_t>(v)].z, pos[static_cast<std::size_t>(v)].z);
    if (v < n || v >= rings * n) {
      EXPECT_EQ(wide[static_cast<std::size_t>(v)], pos[static_cast<std::size_t>(v)]);
    }
  }
}

// A hole that crosses its outer contour (an endocardium drawn across the epicardium): no cap exists, and
// the cap says so (exit code 16) instead of indexing vertices the crossing made (a crash before).
TEST(Cap, CrossingLoopsAreRefusedNotTriangulated) {
  std::vector<c4d::Vec2> outer, hole;
  for (int k = 0; k < 40; ++k) {
    const double t = 2 * M_PI * k / 40;
    outer.push_back({10 * std::cos(t), 10 * std::sin(t)});
    hole.push_back({6 + 6 * std::cos(-t), 6 * std::sin(-t)});  // reaches out to x = 12
  }
  try {
    c4d::triangulate_cap({outer, hole}, c4d::CapStyle::Rounded, {1.0, 2.0});
    ADD_FAILURE() << "crossing loops triangulated";
  } catch (const c4d::Error& e) {
    EXPECT_EQ(e.code(), c4d::ErrorCode::SelfIntersection) << e.what();
  }
}

}  // namespace
