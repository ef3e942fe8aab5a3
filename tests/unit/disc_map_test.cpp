// One disc laid onto another (disc_map.h), on families of random domes drawn from seeds (elliptic borders,
// heights, ring and sector counts, tilts): the flattening puts the border on the unit circle and folds no
// triangle, a disc lifted onto itself comes back unchanged, and a dome laid onto another dome of another size
// and triangulation lands on it with every triangle facing the same way (no fold).
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "contour4d/core/normals.h"
#include "contour4d/metrics/surface_projector.h"
#include "contour4d/motion/disc_map.h"

namespace c4d {
namespace {

// A dome over an ellipse (semi-axes a, b) of height h, `rings` rings of `sectors` points around a centre;
// the border is the outer ring, counter-clockwise about +z, its first point at angle `phase`.
struct Dome {
  std::vector<Vec3> x;
  Disc disc;
  std::vector<Vec3> border_curve;  // the ellipse, finely sampled: the curve both domes share
};

Dome make_dome(double a, double b, double h, int rings, int sectors, double phase) {
  Dome d;
  d.x.push_back({0, 0, h});
  for (int r = 1; r <= rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      const double t = phase + 2.0 * std::numbers::pi * s / sectors, rho = static_cast<double>(r) / rings;
      d.x.push_back({rho * a * std::cos(t), rho * b * std::sin(t), h * (1.0 - rho * rho)});
    }
  auto id = [&](int r, int s) { return static_cast<std::uint32_t>(r == 0 ? 0 : 1 + (r - 1) * sectors + s % sectors); };
  for (int s = 0; s < sectors; ++s) d.disc.triangles.push_back({id(0, 0), id(1, s), id(1, s + 1)});
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      d.disc.triangles.push_back({id(r, s), id(r + 1, s), id(r + 1, s + 1)});
      d.disc.triangles.push_back({id(r, s), id(r + 1, s + 1), id(r, s + 1)});
    }
  for (int s = 0; s < sectors; ++s) d.disc.border.push_back(id(rings, s));
  for (int k = 0; k < 2000; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 2000;
    d.border_curve.push_back({a * std::cos(t), b * std::sin(t), 0});
  }
  return d;
}

double signed_area(Vec2 a, Vec2 b, Vec2 c) { return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)); }

std::vector<double> border_turns(const Dome& d) {
  std::vector<Vec3> p;
  for (std::uint32_t v : d.disc.border) p.push_back(d.x[v]);
  return turns_along(d.border_curve, p);
}

TEST(DiscMap, TurnsAlongALoopAreArcLengthShares) {
  const std::vector<Vec3> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<double> t = turns_along(square, {{0.5, 0, 0}, {1, 0.5, 0}, {0.25, 1.2, 0}, {-0.1, 0.5, 0}});
  EXPECT_NEAR(t[0], 0.125, 1e-12);
  EXPECT_NEAR(t[1], 0.375, 1e-12);
  EXPECT_NEAR(t[2], 0.6875, 1e-12);
  EXPECT_NEAR(t[3], 0.875, 1e-12);
}

TEST(DiscMap, FlatteningFamilyPutsTheBorderOnTheCircleAndFoldsNothing) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Dome d = make_dome(10 + 20 * u(rng), 6 + 15 * u(rng), 25 * u(rng), 3 + static_cast<int>(12 * u(rng)),
                             8 + static_cast<int>(60 * u(rng)), 6.28 * u(rng));
    const std::vector<Vec2> uv = flatten_disc(d.x, d.disc, border_turns(d));
    for (std::uint32_t v : d.disc.border) EXPECT_NEAR(std::hypot(uv[v].x, uv[v].y), 1.0, 1e-12) << "seed " << seed;
    int positive = 0, negative = 0;
    for (const Triangle& t : d.disc.triangles) {
      const double area = signed_area(uv[t[0]], uv[t[1]], uv[t[2]]);
      positive += area > 1e-14;
      negative += area < -1e-14;
    }
    EXPECT_TRUE(positive == 0 || negative == 0) << "seed " << seed << ": " << positive << " vs " << negative;
    EXPECT_EQ(positive + negative, static_cast<int>(d.disc.triangles.size())) << "seed " << seed;
  }
}

TEST(DiscMap, ADiscLiftedOntoItselfComesBackUnchanged) {
  const Dome d = make_dome(20, 12, 10, 6, 40, 0.3);
  const std::vector<Vec2> uv = flatten_disc(d.x, d.disc, border_turns(d));
  const std::vector<Vec3> back = lift_from_disc(uv, d.x, d.disc, uv);
  for (std::size_t v = 0; v < d.x.size(); ++v) EXPECT_LT(norm(back[v] - d.x[v]), 1e-9) << v;
}

TEST(DiscMap, DomeFamilyLandsOnAnotherDomeWithoutFolds) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(100 + seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double a = 10 + 20 * u(rng), b = 6 + 15 * u(rng);
    // A tall dome with fine rings (a band and a cap) onto a low one over the same border, meshed otherwise.
    const Dome from = make_dome(a, b, 15 + 20 * u(rng), 8 + static_cast<int>(10 * u(rng)),
                                24 + static_cast<int>(50 * u(rng)), 6.28 * u(rng));
    const Dome onto = make_dome(a, b, 2 + 6 * u(rng), 4 + static_cast<int>(6 * u(rng)),
                                16 + static_cast<int>(40 * u(rng)), 6.28 * u(rng));
    const std::vector<Vec2> uv_from = flatten_disc(from.x, from.disc, border_turns(from));
    const std::vector<Vec2> uv_onto = flatten_disc(onto.x, onto.disc, border_turns(onto));
    std::vector<Vec2> where;
    for (std::size_t v = 0; v < from.x.size(); ++v) where.push_back(uv_from[v]);
    std::vector<Vec3> y = lift_from_disc(where, onto.x, onto.disc, uv_onto);
    const SurfaceProjector surface(TriangleMesh{onto.x, onto.disc.triangles});
    for (std::size_t v = 0; v < y.size(); ++v)
      EXPECT_LT(norm(surface.closest(y[v]) - y[v]), 1e-9) << "seed " << seed << " vertex " << v;
    for (const Triangle& t : from.disc.triangles) {
      const Vec3 n = cross(y[t[1]] - y[t[0]], y[t[2]] - y[t[0]]);
      EXPECT_GT(n.z, 0.0) << "seed " << seed << ": a triangle turned over";
    }
  }
}

}  // namespace
}  // namespace c4d
