// Topology checks of the reconstructed surface (Lim et al. 2014 ask for "a complete closed
// manifold"): half-edge pairing, fans around vertices, Euler characteristic, and CGAL's
// self-intersection test (box intersection then exact triangle tests).
#include "contour4d/surface/mesh_check.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <stdexcept>
#include <string>

#include "contour4d/core/union_find.h"
#include "contour4d/metrics/topology.h"

namespace c4d {
namespace {

struct HalfEdge {
  std::uint32_t lo, hi;  // sorted endpoints
  std::uint32_t tri;
  std::uint8_t corner_lo, corner_hi;  // the first corner of tri at lo, at hi
  bool forward;                       // runs lo -> hi
};

std::uint8_t corner(const Triangle& t, std::uint32_t v) { return t[0] == v ? 0 : (t[1] == v ? 1 : 2); }

bool soup_self_intersects(const TriangleMesh& mesh) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SM = CGAL::Surface_mesh<K::Point_3>;
  SM sm;
  std::vector<SM::Vertex_index> vid;
  for (const Vec3& p : mesh.positions) vid.push_back(sm.add_vertex(K::Point_3(p.x, p.y, p.z)));
  for (const Triangle& t : mesh.triangles)
    if (sm.add_face(vid[t[0]], vid[t[1]], vid[t[2]]) == SM::null_face()) return true;  // not a manifold surface
  return CGAL::Polygon_mesh_processing::does_self_intersect(sm);
}

}  // namespace

std::vector<std::array<std::uint32_t, 2>> self_intersecting_pairs(const TriangleMesh& mesh) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SM = CGAL::Surface_mesh<K::Point_3>;
  SM sm;
  std::vector<SM::Vertex_index> vid;
  for (const Vec3& p : mesh.positions) vid.push_back(sm.add_vertex(K::Point_3(p.x, p.y, p.z)));
  std::vector<std::array<std::uint32_t, 2>> out;
  for (const Triangle& t : mesh.triangles)
    if (sm.add_face(vid[t[0]], vid[t[1]], vid[t[2]]) == SM::null_face()) return out;
  std::vector<std::pair<SM::Face_index, SM::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
  for (const auto& [a, b] : pairs) out.push_back({std::min<std::uint32_t>(a, b), std::max<std::uint32_t>(a, b)});
  std::sort(out.begin(), out.end());
  return out;
}

MeshCheck check_mesh(const TriangleMesh& mesh, bool self_intersections) {
  MeshCheck c;
  const std::size_t nt = mesh.triangles.size();
  // Triangles and corners are numbered in 32 bits below (half the memory traffic of the sort and the
  // disjoint sets); such a mesh would take more than 17 GB of triangles alone.
  if (nt > UINT32_MAX / 3)
    throw std::length_error("check_mesh: more than " + std::to_string(UINT32_MAX / 3) + " triangles");
  // Half-edges grouped by their lower endpoint (a counting sort), each group then sorted by upper
  // endpoint and triangle: the order of one sort by (lo, hi, tri), in linear time.
  const std::size_t nv = mesh.positions.size();
  std::vector<char> used(nv, 0);
  std::vector<std::size_t> start(nv + 1, 0);
  for (std::size_t f = 0; f < nt; ++f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
        norm(cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]])) == 0.0)
      ++c.degenerate_triangles;
    for (int k = 0; k < 3; ++k) {
      used[t[k]] = 1;
      ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
    }
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<HalfEdge> hes(3 * nt);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < nt; ++f) {
      const Triangle& t = mesh.triangles[f];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = t[k], b = t[(k + 1) % 3], lo = std::min(a, b), hi = std::max(a, b);
        hes[fill[lo]++] = {lo, hi, static_cast<std::uint32_t>(f), corner(t, lo), corner(t, hi), a < b};
      }
    }
  }
  for (std::size_t v = 0; v < nv; ++v)
    std::sort(hes.begin() + static_cast<std::ptrdiff_t>(start[v]),
              hes.begin() + static_cast<std::ptrdiff_t>(start[v + 1]),
              [](const HalfEdge& x, const HalfEdge& y) { return x.hi != y.hi ? x.hi < y.hi : x.tri < y.tri; });
  DisjointSets<std::uint32_t> faces(nt), corners(3 * nt);
  std::size_t edges = 0;
  for (std::size_t i = 0; i < hes.size();) {
    std::size_t j = i;
    while (j < hes.size() && hes[j].lo == hes[i].lo && hes[j].hi == hes[i].hi) ++j;
    ++edges;
    const std::size_t count = j - i;
    if (count == 1) ++c.boundary_edges;
    if (count > 2) ++c.nonmanifold_edges;
    if (count == 2) {
      if (hes[i].forward == hes[i + 1].forward) ++c.misoriented_edges;
      const std::size_t t1 = hes[i].tri, t2 = hes[i + 1].tri;
      corners.unite(3 * t1 + hes[i].corner_lo, 3 * t2 + hes[i + 1].corner_lo);
      corners.unite(3 * t1 + hes[i].corner_hi, 3 * t2 + hes[i + 1].corner_hi);
    }
    for (auto it = hes.begin() + static_cast<std::ptrdiff_t>(i + 1); it != hes.begin() + static_cast<std::ptrdiff_t>(j);
         ++it)
      faces.unite(hes[i].tri, it->tri);
    i = j;
  }
  // A vertex is manifold when its corners form one fan.
  std::vector<std::size_t> first_root(mesh.positions.size(), SIZE_MAX);
  std::vector<char> bad(mesh.positions.size(), 0);
  for (std::size_t f = 0; f < nt; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.triangles[f][k];
      const std::size_t r = corners.find(3 * f + k);
      if (first_root[v] == SIZE_MAX)
        first_root[v] = r;
      else if (first_root[v] != r && !bad[v]) {
        bad[v] = 1;
        ++c.nonmanifold_vertices;
      }
    }
  for (std::size_t f = 0; f < nt; ++f)
    if (faces.find(f) == f) ++c.components;
  const long used_vertices = static_cast<long>(std::count(used.begin(), used.end(), 1));
  c.euler = used_vertices - static_cast<long>(edges) + static_cast<long>(nt);
  c.signed_volume = signed_volume(mesh);
  // A clean closed surface (the usual case) by the soup test, whose vertex fans spare most pairs
  // (metrics/topology.h: the same rule as CGAL's); anything else by CGAL's test on a Surface_mesh.
  const bool clean = c.boundary_edges == 0 && c.nonmanifold_edges == 0 && c.nonmanifold_vertices == 0 &&
                     c.misoriented_edges == 0 && c.degenerate_triangles == 0;
  if (self_intersections && nt > 0)
    c.self_intersects = clean ? count_self_intersections(mesh) > 0 : soup_self_intersects(mesh);
  return c;
}

}  // namespace c4d
