// Mesh–plane section by edge crossings. Each triangle with vertices on both sides contributes one
// segment between two crossed edges; segments are chained through their shared edges into loops.
#include "contour4d/motion/section.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>

namespace c4d {

std::vector<std::vector<Vec3>> plane_section(const TriangleMesh& mesh, const Plane& plane) {
  using EdgeKey = std::pair<std::uint32_t, std::uint32_t>;
  auto key = [](std::uint32_t a, std::uint32_t b) { return a < b ? EdgeKey{a, b} : EdgeKey{b, a}; };
  std::vector<double> d(mesh.positions.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = signed_distance(plane, mesh.positions[i]);
  auto above = [&](std::uint32_t v) { return d[v] >= 0.0; };

  // next[e] = the crossed edge that follows e in the loop (walking each triangle's segment one way).
  std::map<EdgeKey, EdgeKey> next;
  for (const Triangle& t : mesh.triangles) {
    const bool a0 = above(t[0]), a1 = above(t[1]), a2 = above(t[2]);
    if (a0 == a1 && a1 == a2) continue;
    // The lone vertex is the one on its own side; the segment runs between its two edges,
    // oriented consistently with the triangle's orientation.
    int lone = (a0 == a1) ? 2 : (a0 == a2 ? 1 : 0);
    const std::uint32_t v = t[static_cast<std::size_t>(lone)];
    const std::uint32_t vn = t[static_cast<std::size_t>((lone + 1) % 3)],
                        vp = t[static_cast<std::size_t>((lone + 2) % 3)];
    EdgeKey from = key(v, vn), to = key(vp, v);
    if (!above(v)) std::swap(from, to);
    next.emplace(from, to);
  }
  auto point = [&](const EdgeKey& e) {
    const double da = d[e.first], db = d[e.second];
    const double t = da / (da - db);
    return mesh.positions[e.first] + t * (mesh.positions[e.second] - mesh.positions[e.first]);
  };
  std::vector<std::vector<Vec3>> loops;
  std::map<EdgeKey, bool> used;
  for (const auto& [start, unused] : next) {
    if (used.count(start)) continue;
    std::vector<Vec3> loop;
    EdgeKey e = start;
    while (!used.count(e)) {
      used[e] = true;
      const Vec3 p = point(e);
      if (loop.empty() || distance(loop.back(), p) > 1e-12) loop.push_back(p);
      const auto it = next.find(e);
      if (it == next.end()) break;  // open chain: the mesh has a hole here
      e = it->second;
    }
    while (loop.size() > 1 && distance(loop.front(), loop.back()) <= 1e-12) loop.pop_back();
    if (loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace c4d
