#pragma once
// Meshes built in code for the metrics and evaluate tests: icosphere, torus, a sphere made of
// latitude rings (whose rings are exact contours of it), and a few ways to break them.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"

namespace c4d::test {

// Icosahedron refined `levels` times, vertices on the sphere of radius r about `center`;
// triangles counter-clockwise seen from outside.
inline TriangleMesh icosphere(double r, int levels, Vec3 center = {}) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.positions.push_back(0.5 * (m.positions[a] + m.positions[b]));
      const auto i = static_cast<std::uint32_t>(m.positions.size() - 1);
      mid[key] = i;
      return i;
    };
    std::vector<Triangle> next;
    for (const Triangle& tr : m.triangles) {
      const std::uint32_t a = midpoint(tr[0], tr[1]), b = midpoint(tr[1], tr[2]), c = midpoint(tr[2], tr[0]);
      next.push_back({tr[0], a, c});
      next.push_back({tr[1], b, a});
      next.push_back({tr[2], c, b});
      next.push_back({a, b, c});
    }
    m.triangles = std::move(next);
  }
  for (Vec3& p : m.positions) p = center + r * normalized(p);
  return m;
}

// Torus around the z axis: tube radius r at distance R, n × k quads split in two.
inline TriangleMesh torus(double R, double r, int n, int k) {
  TriangleMesh m;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      const double u = 2 * std::numbers::pi * i / n, v = 2 * std::numbers::pi * j / k;
      m.positions.push_back(
          {(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(((i + n) % n) * k + (j + k) % k); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  if (signed_volume(m) < 0)
    for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// A sphere made of `rings` latitude rings of `per_ring` vertices each plus two poles; ring i lies
// on the plane z = center.z + r cos(theta_i). Rings are exact polygons of the mesh (its edges).
inline TriangleMesh ring_sphere(double r, int rings, int per_ring, Vec3 center = {}) {
  TriangleMesh m;
  m.positions.push_back(center + Vec3{0, 0, -r});  // south pole
  for (int i = 0; i < rings; ++i) {
    const double th = std::numbers::pi * (rings - i) / (rings + 1);  // from the south upward
    for (int j = 0; j < per_ring; ++j) {
      const double ph = 2 * std::numbers::pi * j / per_ring;
      m.positions.push_back(center +
                            Vec3{r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
    }
  }
  m.positions.push_back(center + Vec3{0, 0, r});  // north pole
  const auto north = static_cast<std::uint32_t>(m.positions.size() - 1);
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(1 + i * per_ring + (j + per_ring) % per_ring); };
  for (int j = 0; j < per_ring; ++j) m.triangles.push_back({0, id(0, j + 1), id(0, j)});
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < per_ring; ++j) {
      m.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  for (int j = 0; j < per_ring; ++j) m.triangles.push_back({north, id(rings - 1, j), id(rings - 1, j + 1)});
  if (signed_volume(m) < 0)
    for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// The rings of ring_sphere(mesh) as one frame of contours (slice i = ring i, normal +z).
inline Frame ring_contours(const TriangleMesh& mesh, int rings, int per_ring) {
  Frame f;
  for (int i = 0; i < rings; ++i) {
    Slice s;
    s.id = i;
    Contour c;
    c.label = "lv";
    c.slice = i;
    for (int j = 0; j < per_ring; ++j) c.points.push_back(mesh.positions[1 + i * per_ring + j]);
    s.offset = c.points[0].z;
    s.contours.push_back(c);
    f.slices.push_back(s);
  }
  return f;
}

// A sequence with the stack normal +z around the given frames.
inline Sequence z_sequence(std::vector<Frame> frames) {
  Sequence seq;
  seq.normal = {0, 0, 1};
  seq.u = {1, 0, 0};
  seq.v = {0, 1, 0};
  for (std::size_t f = 0; f < frames.size(); ++f) frames[f].time_ms = 40.0 * static_cast<double>(f);
  seq.frames = std::move(frames);
  return seq;
}

// Frame f of a "beating" shape: x and y scaled by a smooth factor (down to 0.85), z kept, so that
// slice planes (z = const) stay put as in cine MRI.
inline TriangleMesh breathe(const TriangleMesh& m, int f) {
  TriangleMesh out = m;
  const double s = 1.0 - 0.15 * std::sin(std::numbers::pi * f / 6.0);
  for (Vec3& p : out.positions) p = {p.x * s, p.y * s, p.z};
  return out;
}

// Deterministic permutation of the positions (triangles unchanged).
inline TriangleMesh shuffle_vertices(const TriangleMesh& m) {
  TriangleMesh out = m;
  const std::size_t n = out.positions.size();
  std::uint64_t state = 12345;
  for (std::size_t i = n - 1; i > 0; --i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    std::swap(out.positions[i], out.positions[(state >> 33) % (i + 1)]);
  }
  return out;
}

}  // namespace c4d::test
