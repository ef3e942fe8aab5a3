// Properties of the core value types and geometry helpers.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "contour4d/core/contour.h"
#include "contour4d/core/errors.h"
#include "contour4d/core/mesh.h"
#include "contour4d/core/plane.h"
#include "contour4d/core/radix_sort.h"

namespace c4d {
namespace {

std::vector<Vec3> circle(double r, int n, double z = 0.0) {
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    p.push_back({r * std::cos(t), r * std::sin(t), z});
  }
  return p;
}

TEST(Plane, FrameIsOrthonormalAndRightHanded) {
  for (Vec3 n : {Vec3{0, 0, 1}, Vec3{1, 0, 0}, Vec3{0.3, -0.7, 0.2}, Vec3{-1, -1, -1}}) {
    const Plane pl = make_plane({1, 2, 3}, n);
    EXPECT_NEAR(norm(pl.u), 1, 1e-12);
    EXPECT_NEAR(norm(pl.v), 1, 1e-12);
    EXPECT_NEAR(dot(pl.u, pl.normal), 0, 1e-12);
    EXPECT_NEAR(dot(pl.v, pl.normal), 0, 1e-12);
    EXPECT_NEAR(distance(cross(pl.u, pl.v), pl.normal), 0, 1e-12);
  }
}

TEST(Plane, ProjectionRoundTrips) {
  const Plane pl = make_plane({1, 2, 3}, {0.3, -0.7, 0.2});
  const Vec3 p{4, -5, 6};
  const Vec2 q = to_plane(pl, p);
  const Vec3 back = from_plane(pl, q, signed_distance(pl, p));
  EXPECT_NEAR(distance(back, p), 0, 1e-12);
}

TEST(Contour, AreaAndPerimeterOfCircle) {
  const int n = 720;
  const auto c = circle(10, n);
  std::vector<Vec2> flat;
  for (const Vec3& p : c) flat.push_back({p.x, p.y});
  const double exact_poly_area = 0.5 * n * 100 * std::sin(2 * std::numbers::pi / n);
  EXPECT_NEAR(signed_area(flat), exact_poly_area, 1e-9);
  std::reverse(flat.begin(), flat.end());
  EXPECT_NEAR(signed_area(flat), -exact_poly_area, 1e-9);
  EXPECT_NEAR(perimeter(c), 2 * n * 10 * std::sin(std::numbers::pi / n), 1e-9);
}

TEST(Contour, SamplingStepsEvenlyAlongTheClosedPolygon) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const auto s = sample_closed_polyline(square, 0.2);
  EXPECT_EQ(s.size(), 20u);
  for (std::size_t i = 0; i < s.size(); ++i)
    EXPECT_NEAR(distance(s[i], s[(i + 1) % s.size()]), 0.2, 0.2 * (1 - std::sqrt(0.5)) + 1e-9);
}

TEST(Contour, SelfIntersectionDetection) {
  const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_FALSE(is_self_intersecting(square));
  const std::vector<Vec2> bowtie{{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  EXPECT_TRUE(is_self_intersecting(bowtie));
  const std::vector<Vec2> touching{{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}};  // vertex on an edge
  EXPECT_TRUE(is_self_intersecting(touching));
  const std::vector<Vec2> spike{{0, 0}, {2, 0}, {1, 0}, {1, 1}};  // folds back on itself
  EXPECT_TRUE(is_self_intersecting(spike));
}

TEST(Mesh, VolumeOfOctahedronIsExactAndInvariantToTranslation) {
  TriangleMesh m;
  m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  EXPECT_NEAR(signed_volume(m), 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(surface_area(m), 8 * std::sqrt(3.0) / 2, 1e-12);
  for (Vec3& p : m.positions) p += Vec3{1000, -2000, 300};
  EXPECT_NEAR(signed_volume(m), 4.0 / 3.0, 1e-9);
}

TEST(Errors, MessageNamesThePlaceAndTheHint) {
  Location where{"a.json"};
  where.line = 3;
  where.frame = 1;
  where.slice = 4;
  where.contour = 0;
  const InvalidInput e(ErrorCode::NonFinite, where, "coordinate is NaN", "Fix the file");
  EXPECT_EQ(std::string(e.what()), "a.json: line 3, frame 1, slice 4, contour 0: coordinate is NaN. Fix the file");
  EXPECT_EQ(e.code(), ErrorCode::NonFinite);
}

}  // namespace
}  // namespace c4d

// sort_pairs gives std::sort's order bit for bit: long and short lists, negative values (the
// remeshing's split list sorts by −length²), many ties on the value (resolved by the id), −0 and +0 as
// equal values, identical items kept.
TEST(RadixSort, GivesStdSortsOrder) {
  std::mt19937_64 rng(7);
  for (const std::size_t n : {0u, 1u, 100u, 511u, 512u, 5000u, 70000u}) {
    for (const bool negative : {false, true}) {
      std::vector<std::pair<double, std::uint64_t>> items;
      std::uniform_real_distribution<double> length(0.1, 0.9);
      for (std::size_t i = 0; i < n; ++i) {
        double v = i % 7 == 0 ? 0.25 : length(rng);  // every seventh the same value
        if (i % 97 == 0) v = i % 2 == 0 ? 0.0 : -0.0;
        items.push_back({negative ? -v : v, rng() % (4 * n + 1)});
        if (i % 50 == 0) items.push_back(items.back());  // duplicates
      }
      std::vector<std::pair<double, std::uint64_t>> expected = items, spare;
      std::sort(expected.begin(), expected.end());
      c4d::sort_pairs(items, spare);
      ASSERT_EQ(items.size(), expected.size());
      for (std::size_t i = 0; i < items.size(); ++i) {
        // −0 and +0 compare equal: std::sort may leave them in either order, so compare as values.
        EXPECT_TRUE(items[i].first == expected[i].first && items[i].second == expected[i].second) << n << " at " << i;
      }
    }
  }
}
