// Lim et al. 2014, "Contour Matching": the mesh's copies of the input contours (chains) and their
// one-to-one partners by the similarity index (eq. 5).
#include "contour4d/motion/chains.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace c4d {

std::vector<Chain> find_chains(const Sequence& seq, const TriangleMesh& mesh) {
  std::map<int, const Slice*> planes;
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices) planes.emplace(s.id, &s);
  double scale = 1.0;
  for (const Vec3& p : mesh.positions) scale = std::max(scale, std::abs(dot(p, seq.normal)));
  const double tol = 1e-7 * scale;
  std::vector<Chain> chains;
  for (const auto& [id, any] : planes) {
    const Plane pl = slice_plane(seq, *any);
    std::vector<char> on(mesh.positions.size());
    for (std::size_t i = 0; i < on.size(); ++i) on[i] = std::abs(signed_distance(pl, mesh.positions[i])) < tol;
    // On-plane edges of triangles that are not entirely on the plane, oriented as the triangle
    // above the plane runs them (a triangle below runs the same edge the other way).
    std::map<std::uint32_t, std::vector<std::uint32_t>> succ;
    for (const Triangle& t : mesh.triangles) {
      if (on[t[0]] && on[t[1]] && on[t[2]]) continue;
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
        const std::uint32_t c = t[static_cast<std::size_t>((k + 2) % 3)];
        if (!on[a] || !on[b]) continue;
        if (signed_distance(pl, mesh.positions[c]) < 0) std::swap(a, b);
        auto& s = succ[a];
        if (std::find(s.begin(), s.end(), b) == s.end()) s.push_back(b);
      }
    }
    std::set<std::uint32_t> used;
    for (const auto& [v0, unused] : succ) {
      if (used.count(v0)) continue;
      std::vector<std::uint32_t> loop;
      std::uint32_t v = v0;
      bool closed = false;
      while (true) {
        if (used.count(v)) {
          closed = (v == v0);
          break;
        }
        used.insert(v);
        loop.push_back(v);
        const auto it = succ.find(v);
        if (it == succ.end() || it->second.size() != 1) break;  // touching contours: not a simple loop
        v = it->second.front();
      }
      if (closed && loop.size() >= 3) chains.push_back({id, pl, std::move(loop)});
    }
  }
  return chains;
}

int one_to_one_partner(const std::vector<std::vector<double>>& sim, std::size_t i, double threshold) {
  int partner = -1, count = 0;
  for (std::size_t j = 0; j < sim[i].size(); ++j)
    if (sim[i][j] > threshold) {
      partner = static_cast<int>(j);
      ++count;
    }
  if (count != 1) return -1;
  int back = 0;
  for (const std::vector<double>& row : sim) back += row[static_cast<std::size_t>(partner)] > threshold;
  return back == 1 ? partner : -1;
}

}  // namespace c4d
