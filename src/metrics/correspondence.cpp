// Vertex correspondence across frames (Lim et al. 2014, "Vertex Correspondence and Mesh Quality":
// "the set of 3D mesh models maintains vertex correspondence throughout").
//
// Equal counts and an equal triangle list are necessary but say nothing about whether vertex k
// of frame f is the same material point as vertex k of frame 0: a frame whose positions were
// permuted keeps the counts and the triangles. Geometry tells: under a permutation a triangle's
// corners become unrelated surface points, so its edges turn into random chords, many times the
// edge length. We compare each edge's length in every frame with its reference length, the
// median of that edge's lengths over all frames (robust as long as fewer than half the frames are
// shuffled; with two frames the reference is frame 0). A frame is suspicious when its median
// relative change exceeds 50 % or when more than 1 % of its edges change length by more than a
// factor of 4. Cardiac motion strains the surface by tens of percent, so neither fires on a
// correct sequence; a full permutation moves the median change to hundreds or thousands of %.
#include "contour4d/metrics/correspondence.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace c4d {

CorrespondenceReport check_correspondence(const std::vector<TriangleMesh>& frames,
                                          const CorrespondenceOptions& options) {
  CorrespondenceReport r;
  const std::size_t nf = frames.size();
  r.median_edge_change_pct.assign(nf, 0.0);
  r.edge_jump_pct.assign(nf, 0.0);
  if (nf == 0) return r;
  const TriangleMesh& m0 = frames[0];
  for (std::size_t f = 1; f < nf; ++f) {
    const TriangleMesh& m = frames[f];
    std::string how;
    if (m.positions.size() != m0.positions.size()) {
      r.same_vertex_count = false;
      how = fmt::format("{} vertices instead of {}", m.positions.size(), m0.positions.size());
    }
    if (m.triangles != m0.triangles) {
      r.same_triangles = false;
      std::string t;
      if (m.triangles.size() != m0.triangles.size()) {
        t = fmt::format("{} triangles instead of {}", m.triangles.size(), m0.triangles.size());
      } else {
        std::size_t k = 0;
        while (m.triangles[k] == m0.triangles[k]) ++k;
        t = fmt::format("triangle {} is ({}, {}, {}) instead of ({}, {}, {})", k, m.triangles[k][0], m.triangles[k][1],
                        m.triangles[k][2], m0.triangles[k][0], m0.triangles[k][1], m0.triangles[k][2]);
      }
      how += (how.empty() ? "" : "; ") + t;
    }
    if (!how.empty() && r.first_differing_frame < 0) {
      r.first_differing_frame = static_cast<int>(f);
      r.difference = how;
    }
  }
  if (r.first_differing_frame >= 0) {
    r.faults.push_back(fmt::format("no vertex correspondence: frame {} differs from frame 0: {}",
                                   r.first_differing_frame, r.difference));
    return r;
  }
  if (nf < 2) return r;

  // Distinct edges of the shared triangle list (valid indices only).
  const std::size_t nv = m0.positions.size();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * m0.triangles.size());
  for (const Triangle& t : m0.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (a < nv && b < nv && a != b) edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  if (edges.empty()) return r;

  // len[e * nf + f]: floats keep 300k triangles × 25 frames near 45 MB.
  std::vector<float> len(edges.size() * nf);
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (std::size_t f = 0; f < nf; ++f)
      len[e * nf + f] =
          static_cast<float>(distance(frames[f].positions[edges[e].first], frames[f].positions[edges[e].second]));
  std::vector<std::vector<float>> change(nf);
  std::vector<std::size_t> jumps(nf, 0), measured(nf, 0);
  std::vector<float> tmp(nf);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const float* l = &len[e * nf];
    double ref = l[0];
    if (nf > 2) {
      std::copy(l, l + nf, tmp.begin());
      std::nth_element(tmp.begin(), tmp.begin() + nf / 2, tmp.end());
      ref = tmp[nf / 2];
    }
    if (!(ref > 0.0)) continue;
    for (std::size_t f = 0; f < nf; ++f) {
      const double ratio = l[f] / ref;
      change[f].push_back(static_cast<float>(std::abs(ratio - 1.0)));
      ++measured[f];
      // Only growth: a permuted vertex turns its edges into chords many edges long, while a band that
      // collapses as its contour vanishes (Miara et al.'s sub-mesh lifetime ending) shrinks its edges.
      if (ratio > options.jump_factor) ++jumps[f];
    }
  }
  for (std::size_t f = 0; f < nf; ++f) {
    if (change[f].empty()) continue;
    auto mid = change[f].begin() + change[f].size() / 2;
    std::nth_element(change[f].begin(), mid, change[f].end());
    r.median_edge_change_pct[f] = 100.0 * *mid;
    r.edge_jump_pct[f] = 100.0 * static_cast<double>(jumps[f]) / static_cast<double>(measured[f]);
    if (r.median_edge_change_pct[f] > options.suspicious_median_change_pct ||
        r.edge_jump_pct[f] > options.suspicious_jump_pct) {
      r.suspicious_frames.push_back(static_cast<int>(f));
      r.faults.push_back(fmt::format(
          "vertex correspondence suspicious: frame {}, median edge-length change {:.1f} %, {:.2f} % of edges grew "
          "longer than {:g}-fold (vertices look permuted)",
          f, r.median_edge_change_pct[f], r.edge_jump_pct[f], options.jump_factor));
    }
  }
  return r;
}

}  // namespace c4d
