// Lim et al. 2014, "Contour Matching": the mesh's copies of the input contours (chains) and their
// one-to-one partners by the similarity index (eq. 5).
#include "contour4d/motion/chains.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

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
    // On-plane edges of triangles that are not entirely on the plane, oriented as the triangle above the plane
    // runs them (a triangle below runs the same edge the other way); where the two triangles at an edge
    // disagree (both on one side), the one whose third vertex lies farther from the plane decides.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<double, std::uint32_t>>
        edge_from;  // → (|height|, first)
    for (const Triangle& t : mesh.triangles) {
      if (on[t[0]] && on[t[1]] && on[t[2]]) continue;
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
        const std::uint32_t c = t[static_cast<std::size_t>((k + 2) % 3)];
        if (!on[a] || !on[b]) continue;
        const double height = signed_distance(pl, mesh.positions[c]);
        if (height < 0) std::swap(a, b);
        const auto [it, first] = edge_from.try_emplace({std::min(a, b), std::max(a, b)}, std::abs(height), a);
        if (!first && std::abs(height) > it->second.first) it->second = {std::abs(height), a};
      }
    }
    // A vertex with several successors (a cap's ear: a triangle of three contour vertices, whose chord is
    // also an edge above the plane) keeps the one whose edge lies on the slice's contour.
    const Slice* mine = nullptr;
    if (!seq.frames.empty())
      for (const Slice& s : seq.frames[0].slices)
        if (s.id == id) mine = &s;
    auto off_contour = [&](std::uint32_t a, std::uint32_t b) {
      const Vec3 m = 0.5 * (mesh.positions[a] + mesh.positions[b]);
      double best = std::numeric_limits<double>::infinity();
      if (mine)
        for (const Contour& c : mine->contours) {
          std::int32_t hint = -1;
          if (c.points.size() >= 2) best = std::min(best, norm(closest_on_loop(c.points, m, hint) - m));
        }
      return best;
    };
    std::map<std::uint32_t, std::vector<std::uint32_t>> succ;
    for (const auto& [edge, from] : edge_from)
      succ[from.second].push_back(from.second == edge.first ? edge.second : edge.first);
    for (auto& [a, next] : succ)
      if (next.size() > 1) {
        const auto best = std::min_element(next.begin(), next.end(), [&](std::uint32_t p, std::uint32_t q) {
          return off_contour(a, p) < off_contour(a, q);
        });
        next = {*best};
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

// Closest point to q on the closed polyline `loop`. `hint` is the segment found last time (-1: none,
// then every segment is tried); the search walks from it while a neighbouring segment is closer, so a
// point that moves a little along the contour costs a few segment tests.
Vec3 closest_on_loop(const std::vector<Vec3>& loop, Vec3 q, std::int32_t& hint) {
  const std::size_t n = loop.size();
  double best = std::numeric_limits<double>::infinity();
  Vec3 bp = q;
  std::size_t bk = 0;
  // Neighbouring segments by a compare, not a division (this runs for every sliding vertex every sweep).
  auto next = [n](std::size_t k) { return k + 1 == n ? 0 : k + 1; };
  auto prev = [n](std::size_t k) { return k == 0 ? n - 1 : k - 1; };
  auto consider = [&](std::size_t k) {  // true when segment k is closer than the best so far
    const Vec3 p = closest_on_segment(loop[k], loop[next(k)], q);
    const double d2 = dot(q - p, q - p);
    if (!(d2 < best)) return false;
    best = d2;
    bp = p;
    bk = k;
    return true;
  };
  if (hint < 0 || static_cast<std::size_t>(hint) >= n) {
    for (std::size_t k = 0; k < n; ++k) consider(k);
  } else {
    consider(static_cast<std::size_t>(hint));
    for (std::size_t steps = 0; steps < n; ++steps)
      if (!consider(next(bk)) && !consider(prev(bk))) break;
  }
  hint = static_cast<std::int32_t>(bk);
  return bp;
}

}  // namespace c4d
