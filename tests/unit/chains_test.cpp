// The mesh's copies of the input contours (chains.h): a loop per contour, also where a cap's triangulation has
// an ear (three contour vertices in one triangle lying in the slice plane, its chord an edge of the dome).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "contour4d/motion/chains.h"

namespace c4d {
namespace {

TEST(Chains, ACapWithAnEarKeepsItsContourLoop) {
  constexpr int n = 8;
  Sequence seq;
  seq.normal = {0, 0, 1};
  seq.u = {1, 0, 0};
  seq.v = {0, 1, 0};
  TriangleMesh m;
  Frame frame;
  for (int level = 0; level < 2; ++level) {
    Slice s;
    s.id = level;
    s.offset = level == 0 ? -5.0 : 0.0;
    Contour c;
    c.slice = level;
    for (int k = 0; k < n; ++k) {
      const double t = 2.0 * std::numbers::pi * k / n;
      c.points.push_back({10 * std::cos(t), 10 * std::sin(t), s.offset});
      m.positions.push_back(c.points.back());
    }
    s.contours.push_back(c);
    frame.slices.push_back(s);
  }
  seq.frames.push_back(frame);
  auto b = [](int k) { return static_cast<std::uint32_t>(k % n); };
  auto p = [](int k) { return static_cast<std::uint32_t>(n + k % n); };
  const auto bottom = static_cast<std::uint32_t>(m.positions.size());
  m.positions.push_back({0, 0, -5});
  const auto apex = static_cast<std::uint32_t>(m.positions.size());
  m.positions.push_back({0, 0, 4});
  for (int k = 0; k < n; ++k) {
    m.triangles.push_back({b(k), b(k + 1), p(k + 1)});  // the band, facing out
    m.triangles.push_back({b(k), p(k + 1), p(k)});
    m.triangles.push_back({bottom, b(k + 1), b(k)});  // a flat bottom lid
  }
  m.triangles.push_back({p(0), p(1), p(2)});  // the ear: in the top plane
  m.triangles.push_back({apex, p(0), p(2)});  // the dome over the chord and the other edges
  for (int k = 2; k < n; ++k) m.triangles.push_back({apex, p(k), p(k + 1)});

  const std::vector<Chain> chains = find_chains(seq, m);
  ASSERT_EQ(chains.size(), 2u);
  for (const Chain& c : chains) {
    EXPECT_EQ(c.loop.size(), static_cast<std::size_t>(n)) << "slice " << c.slice;
    for (std::size_t k = 0; k < c.loop.size(); ++k) {  // consecutive contour points, one way round
      const std::uint32_t a = c.loop[k] % n, next = c.loop[(k + 1) % c.loop.size()] % n;
      EXPECT_TRUE(next == (a + 1) % n || a == (next + 1) % n) << "slice " << c.slice;
    }
  }
}

}  // namespace
}  // namespace c4d
