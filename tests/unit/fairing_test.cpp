// Thin-plate fairing (surface/fairing.h): the per-row scale of FairingOptions.
#include "contour4d/surface/fairing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace {

// An open tube of `rows` rings of `around` vertices (radius 5 mm, rings 1 mm apart), its end rings and
// middle ring fixed, the rest pushed out by a bump to be faired away.
struct Tube {
  c4d::TriangleMesh mesh;
  std::vector<char> fixed;
};

Tube bumpy_tube(int around, int rows) {
  Tube t;
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k < around; ++k) {
      const double a = 2.0 * 3.14159265358979323846 * k / around;
      const bool hold = r == 0 || r == rows - 1 || r == rows / 2;
      const double radius = hold ? 5.0 : 5.0 + 0.7 * std::sin(3.0 * a) * std::sin(0.9 * r);
      t.mesh.positions.push_back({radius * std::cos(a), radius * std::sin(a), static_cast<double>(r)});
      t.fixed.push_back(hold ? 1 : 0);
    }
  for (int r = 0; r + 1 < rows; ++r)
    for (int k = 0; k < around; ++k) {
      const auto v = [&](int rr, int kk) { return static_cast<std::uint32_t>(rr * around + (kk % around)); };
      t.mesh.triangles.push_back({v(r, k), v(r, k + 1), v(r + 1, k + 1)});
      t.mesh.triangles.push_back({v(r, k), v(r + 1, k + 1), v(r + 1, k)});
    }
  return t;
}

double max_difference(const c4d::TriangleMesh& a, const c4d::TriangleMesh& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.positions.size(); ++i) d = std::max(d, c4d::distance(a.positions[i], b.positions[i]));
  return d;
}

}  // namespace

// A scale of 1 on every row is no scale at all (bit for bit); the same scale on every row leaves the
// minimiser where it was; a scale on some rows moves it.
TEST(Fairing, RowScaleWeighsTheTermsOfItsVertices) {
  const Tube tube = bumpy_tube(24, 13);
  const std::size_t nv = tube.mesh.positions.size();
  auto faired = [&](const std::vector<double>& scale) {
    c4d::TriangleMesh m = tube.mesh;
    c4d::FairingOptions o;
    o.row_scale = scale;
    EXPECT_TRUE(c4d::fair_thin_plate(m, tube.fixed, {}, o));
    return m;
  };
  const c4d::TriangleMesh plain = faired({});
  EXPECT_GT(max_difference(plain, tube.mesh), 0.1);  // the bumps went
  EXPECT_EQ(faired(std::vector<double>(nv, 1.0)).positions, plain.positions);
  EXPECT_LT(max_difference(faired(std::vector<double>(nv, 0.5)), plain), 1e-9);
  std::vector<double> half(nv, 1.0);
  for (std::size_t v = 0; v < nv / 2; ++v) half[v] = 0.5;  // the lower half's rows weigh a quarter
  EXPECT_GT(max_difference(faired(half), plain), 1e-3);
}

// Scale-aware terms (FairingOptions::scale_aware): the reference length scales every such term alike,
// so where every term is scale-aware the minimiser stays; scaling the mesh and the reference together
// scales the result; they move the minimiser away from the uniform one on a mesh whose edges differ;
// and a vertex on top of a neighbour keeps its uniform term (no infinite weight). Their purpose, slopes matched across a change of mesh
// density, is measured on the torus's caps (ReconstructPhantoms.AccuracyVolumeAndQuality).
TEST(Fairing, ScaleAwareTermsDependOnlyOnTheEdgesRatios) {
  const Tube tube = bumpy_tube(24, 13);
  const std::size_t nv = tube.mesh.positions.size();
  auto faired = [&](const c4d::TriangleMesh& mesh, const std::vector<char>& aware, double reference) {
    c4d::TriangleMesh m = mesh;
    c4d::FairingOptions o;
    o.scale_aware = aware;
    o.reference_edge = reference;
    EXPECT_TRUE(c4d::fair_thin_plate(m, tube.fixed, {}, o));
    for (const c4d::Vec3& p : m.positions) EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    return m;
  };
  std::vector<char> aware(nv, 0);
  for (std::size_t v = 0; v < nv / 2; ++v) aware[v] = 1;  // the lower half's terms
  const c4d::TriangleMesh uniform = faired(tube.mesh, {}, 1.0);
  const c4d::TriangleMesh scaled = faired(tube.mesh, aware, 1.0);
  EXPECT_GT(max_difference(scaled, uniform), 1e-3);
  const std::vector<char> all(nv, 1);
  EXPECT_LT(max_difference(faired(tube.mesh, all, 3.0), faired(tube.mesh, all, 1.0)), 1e-9);
  c4d::TriangleMesh big = tube.mesh;
  for (c4d::Vec3& p : big.positions) p = 2.5 * p;
  c4d::TriangleMesh big_faired = faired(big, aware, 2.5);
  for (c4d::Vec3& p : big_faired.positions) p = (1.0 / 2.5) * p;
  EXPECT_LT(max_difference(big_faired, scaled), 1e-9);
  // A free vertex moved onto its fixed neighbour below: its term stays uniform, the result finite.
  c4d::TriangleMesh pinched = tube.mesh;
  pinched.positions[24 + 5] = pinched.positions[5];
  faired(pinched, all, 1.0);
}
