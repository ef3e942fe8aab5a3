// Tree-based connectivity: Lim et al. 2014 (PLOS ONE 9(4): e93747), section "Tree-Based
// Connectivity" (pseudocode above/below and prev/next, then Kruskal's algorithm with the
// thresholded links fixed). Kruskal, "On the shortest spanning subtree of a graph", 1956.
#include "contour4d/connect/connectivity.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <tuple>

#include "contour4d/connect/similarity.h"
#include "contour4d/core/errors.h"

#include "contour4d/core/union_find.h"

namespace c4d {
namespace {

std::vector<Vec2> project(const Sequence& seq, const Slice& s, const Contour& c) {
  const Plane pl = slice_plane(seq, s);
  std::vector<Vec2> out;
  out.reserve(c.points.size());
  for (const Vec3& p : c.points) out.push_back(to_plane(pl, p));
  return out;
}

std::vector<std::vector<Vec2>> project_slice(const Sequence& seq, const Slice& s) {
  std::vector<std::vector<Vec2>> out;
  for (const Contour& c : s.contours) out.push_back(project(seq, s, c));
  return out;
}

struct Node {
  int frame, slice, contour;
};

}  // namespace

std::vector<int> nesting_depths(const std::vector<std::vector<Vec2>>& polygons) {
  std::vector<int> depth(polygons.size(), 0);
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    if (polygons[i].empty()) continue;
    // Contours of a slice do not cross, so "inside" is all or nothing; the perimeter share makes the
    // test robust to contours that touch at a vertex.
    for (std::size_t j = 0; j < polygons.size(); ++j)
      if (j != i && polygons[j].size() >= 3 && perimeter_inside(polygons[i], polygons[j]) > 0.5) ++depth[i];
  }
  return depth;
}

std::vector<int> threshold_then_kruskal(int n, const std::vector<WeightedEdge>& edges, double threshold,
                                        bool complete_tree) {
  UnionFind uf(n);
  std::vector<int> chosen;
  std::vector<int> order(edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const WeightedEdge &ea = edges[a], &eb = edges[b];
    if (ea.weight != eb.weight) return ea.weight > eb.weight;
    if (ea.i != eb.i) return ea.i < eb.i;
    return ea.j < eb.j;
  });
  for (int k : order)
    if (edges[k].weight > threshold) {
      uf.unite(edges[k].i, edges[k].j);
      chosen.push_back(k);
    }
  if (complete_tree)
    for (int k : order)
      if (edges[k].weight > 0.0 && edges[k].weight <= threshold && uf.unite(edges[k].i, edges[k].j))
        chosen.push_back(k);
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

std::vector<Connection> intra_frame_connections(const Sequence& seq, int frame, const ConnectivityOptions& options) {
  if (frame < 0 || frame >= static_cast<int>(seq.frames.size())) {
    Location loc;
    loc.file = seq.source;
    loc.frame = frame;
    throw InvalidInput(ErrorCode::Usage, loc,
                       "frame " + std::to_string(frame) + " does not exist (the input has " +
                           std::to_string(seq.frames.size()) + " frames)",
                       "pick a frame index from 0 to the frame count - 1");
  }
  const Frame& f = seq.frames[static_cast<std::size_t>(frame)];
  std::vector<std::vector<std::vector<Vec2>>> polys;
  std::vector<std::vector<int>> depths;
  std::vector<Node> nodes;
  std::vector<std::vector<int>> node_of;
  for (std::size_t s = 0; s < f.slices.size(); ++s) {
    polys.push_back(project_slice(seq, f.slices[s]));
    depths.push_back(nesting_depths(polys.back()));
    node_of.emplace_back();
    for (std::size_t c = 0; c < f.slices[s].contours.size(); ++c) {
      node_of.back().push_back(static_cast<int>(nodes.size()));
      nodes.push_back({frame, static_cast<int>(s), static_cast<int>(c)});
    }
  }
  std::vector<WeightedEdge> edges;
  for (std::size_t s = 0; s + 1 < f.slices.size(); ++s)
    for (std::size_t a = 0; a < polys[s].size(); ++a)
      for (std::size_t b = 0; b < polys[s + 1].size(); ++b) {
        if (options.respect_nesting && (depths[s][a] - depths[s + 1][b]) % 2 != 0) continue;
        const double sim = contour_similarity(polys[s][a], polys[s + 1][b]);
        if (sim > 0.0) edges.push_back({node_of[s][a], node_of[s + 1][b], sim});
      }
  std::vector<Connection> out;
  for (int k :
       threshold_then_kruskal(static_cast<int>(nodes.size()), edges, options.threshold, options.complete_tree)) {
    const Node& na = nodes[edges[k].i];
    const Node& nb = nodes[edges[k].j];
    out.push_back({frame, f.slices[na.slice].id, na.contour, frame, f.slices[nb.slice].id, nb.contour, edges[k].weight,
                   edges[k].weight > options.threshold});
  }
  return out;
}

std::vector<Connection> inter_frame_connections(const Sequence& seq, const ConnectivityOptions& options) {
  // Group, per slice id, the contours of every frame; links join frames t and t+1 only.
  std::vector<int> ids;
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices) ids.push_back(s.id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<Connection> out;
  for (int id : ids) {
    std::vector<Node> nodes;
    std::vector<std::vector<Vec2>> polys;
    std::vector<int> depth;
    std::vector<std::vector<int>> per_frame(seq.frames.size());
    for (std::size_t t = 0; t < seq.frames.size(); ++t)
      for (const Slice& s : seq.frames[t].slices)
        if (s.id == id) {
          auto ps = project_slice(seq, s);
          auto ds = nesting_depths(ps);
          for (std::size_t c = 0; c < ps.size(); ++c) {
            per_frame[t].push_back(static_cast<int>(nodes.size()));
            nodes.push_back({static_cast<int>(t), id, static_cast<int>(c)});
            polys.push_back(std::move(ps[c]));
            depth.push_back(ds[c]);
          }
        }
    std::vector<WeightedEdge> edges;
    for (std::size_t t = 0; t + 1 < seq.frames.size(); ++t)
      for (int a : per_frame[t])
        for (int b : per_frame[t + 1]) {
          if (options.respect_nesting && (depth[a] - depth[b]) % 2 != 0) continue;
          const double sim = contour_similarity(polys[a], polys[b]);
          if (sim > 0.0) edges.push_back({a, b, sim});
        }
    for (int k :
         threshold_then_kruskal(static_cast<int>(nodes.size()), edges, options.threshold, options.complete_tree)) {
      const Node& na = nodes[edges[k].i];
      const Node& nb = nodes[edges[k].j];
      out.push_back(
          {na.frame, id, na.contour, nb.frame, id, nb.contour, edges[k].weight, edges[k].weight > options.threshold});
    }
  }
  std::sort(out.begin(), out.end(), [](const Connection& x, const Connection& y) {
    return std::tie(x.frame_a, x.slice_a, x.contour_a, x.frame_b, x.contour_b) <
           std::tie(y.frame_a, y.slice_a, y.contour_a, y.frame_b, y.contour_b);
  });
  return out;
}

}  // namespace c4d
