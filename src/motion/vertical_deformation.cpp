// 2D contour topology changes: direction of the vertical motion, ridge, sine vertical deformation.
//
// Reference: Lim C.W., Su Y., Yeo S.Y., et al. "Automatic 4D Reconstruction of Patient-Specific
// Cardiac Mesh with 1-to-1 Vertex Correspondence from Segmented Contours Lines", PLOS ONE 9(4),
// 2014, section "Handling 2D Contour Topological Changes": "Determining Vertical Motion",
// "Ridge Detection" (Fig. 8), "Applying Vertical Motion" (eq. 10, Table 1).
// Choices where the paper is vague are listed in docs/algorithms/vertical_deformation.md.

#include "contour4d/motion/vertical_deformation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <string>
#include <utility>

#include "contour4d/connect/similarity.h"
#include "contour4d/core/contour.h"
#include "contour4d/core/errors.h"
#include "contour4d/core/plane.h"

namespace c4d {

namespace {

const Slice* find_slice(const Frame& f, int id) {
  for (const Slice& s : f.slices)
    if (s.id == id) return &s;
  return nullptr;
}

int count_on(const Frame& f, int id) {
  const Slice* s = find_slice(f, id);
  return s ? static_cast<int>(s->contours.size()) : 0;
}

// Contours of slice `id` in frame `f`, in the shared (u, v) plane coordinates of the stack.
std::vector<std::vector<Vec2>> polygons_on(const Sequence& seq, const Frame& f, int id) {
  std::vector<std::vector<Vec2>> out;
  const Slice* s = find_slice(f, id);
  if (!s) return out;
  const Plane pl = slice_plane(seq, *s);
  for (const Contour& c : s->contours) {
    std::vector<Vec2> poly;
    poly.reserve(c.points.size());
    for (Vec3 p : c.points) poly.push_back(to_plane(pl, p));
    out.push_back(std::move(poly));
  }
  return out;
}

// Every slice id of the sequence with its offset, by increasing offset. Offsets of one id are
// equal in every frame (build_sequence guarantees one plane per id).
std::vector<std::pair<double, int>> slice_order(const Sequence& seq) {
  std::map<int, double> offset_of;
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices) offset_of.emplace(s.id, s.offset);
  std::vector<std::pair<double, int>> order;
  for (const auto& [id, off] : offset_of) order.emplace_back(off, id);
  std::sort(order.begin(), order.end());
  return order;
}

void check_frames(const Sequence& seq, int frame, int next_frame) {
  const int n = static_cast<int>(seq.frames.size());
  if (frame < 0 || frame >= n || next_frame < 0 || next_frame >= n) {
    Location where;
    where.file = seq.source;
    where.frame = frame < 0 || frame >= n ? frame : next_frame;
    throw InvalidInput(ErrorCode::Internal, where,
                       std::string(__func__) + ": frame index out of range (" + std::to_string(n) + " frames)",
                       "pass frame indices of the sequence");
  }
}

// Distance (mm) from p to a closed polygon (or a single point / open polyline when closed = false).
std::vector<std::vector<std::uint32_t>> vertex_neighbours(const TriangleMesh& mesh) {
  std::vector<std::vector<std::uint32_t>> nb(mesh.positions.size());
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (a >= nb.size() || b >= nb.size()) continue;
      nb[a].push_back(b);
      nb[b].push_back(a);
    }
  for (auto& l : nb) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  return nb;
}

// Dijkstra over mesh edges; ties by vertex id, so the path is deterministic.
std::vector<std::uint32_t> shortest_path(const TriangleMesh& mesh, const std::vector<std::vector<std::uint32_t>>& nb,
                                         std::uint32_t from, std::uint32_t to,
                                         const std::function<bool(std::uint32_t)>& allowed) {
  const std::size_t n = mesh.positions.size();
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<std::uint32_t> prev(n, std::numeric_limits<std::uint32_t>::max());
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[from] = 0.0;
  queue.emplace(0.0, from);
  while (!queue.empty()) {
    const auto [d, a] = queue.top();
    queue.pop();
    if (d > dist[a]) continue;
    if (a == to) break;
    for (std::uint32_t b : nb[a]) {
      if (!allowed(b)) continue;
      const double nd = d + distance(mesh.positions[a], mesh.positions[b]);
      if (nd < dist[b]) {
        dist[b] = nd;
        prev[b] = a;
        queue.emplace(nd, b);
      }
    }
  }
  if (!std::isfinite(dist[to])) return {};
  std::vector<std::uint32_t> path;
  for (std::uint32_t a = to; a != from; a = prev[a]) path.push_back(a);
  path.push_back(from);
  std::reverse(path.begin(), path.end());
  return path;
}

std::uint32_t nearest_vertex(const TriangleMesh& mesh, Vec3 p) {
  std::uint32_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const double d = distance(mesh.positions[i], p);
    if (d < best_d) best_d = d, best = static_cast<std::uint32_t>(i);
  }
  return best;
}

double mean_height(const std::vector<Vec3>& pts, Vec3 normal) {
  double h = 0.0;
  for (Vec3 p : pts) h += dot(p, normal);
  return pts.empty() ? 0.0 : h / static_cast<double>(pts.size());
}

// Linear interpolation of R between the six slice heights; a linear taper to zero beyond them.
double r_at(const VerticalField& f, double h) {
  const auto& H = f.heights;
  if (h > H[0]) return f.taper > 0.0 && h < H[0] + f.taper ? f.r[0] * (1.0 - (h - H[0]) / f.taper) : 0.0;
  if (h < H[5]) return f.taper > 0.0 && h > H[5] - f.taper ? f.r[5] * (1.0 - (H[5] - h) / f.taper) : 0.0;
  for (int k = 0; k < 5; ++k) {
    if (h >= H[k + 1]) {
      const double gap = H[k] - H[k + 1];
      const double s = gap > 0.0 ? (H[k] - h) / gap : 0.0;
      return (1.0 - s) * f.r[k] + s * f.r[k + 1];
    }
  }
  return f.r[5];
}

}  // namespace

VerticalMotion vertical_motion_direction(const Sequence& seq, int frame, int next_frame, int slice_id,
                                         const VerticalDeformationOptions& options) {
  check_frames(seq, frame, next_frame);
  const Frame& f0 = seq.frames[frame];
  const Frame& f1 = seq.frames[next_frame];
  VerticalMotion m;
  m.frame = frame;
  m.next_frame = next_frame;
  m.incident_slice = slice_id;
  m.contours_before = count_on(f0, slice_id);
  m.contours_after = count_on(f1, slice_id);
  const int before = m.contours_before, after = m.contours_after;
  if (before == after) return m;
  if (before == 0)
    m.event = ContourEvent::Appear;
  else if (after == 0)
    m.event = ContourEvent::Vanish;
  else
    m.event = after > before ? ContourEvent::Split : ContourEvent::Merge;
  if (m.event == ContourEvent::Appear || m.event == ContourEvent::Vanish) return m;

  // Neighbours by offset over the whole sequence (a slice without contours in a frame counts 0).
  const auto order = slice_order(seq);
  int below = -1, above = -1;
  for (std::size_t k = 0; k < order.size(); ++k)
    if (order[k].second == slice_id) {
      if (k > 0) below = order[k - 1].second;
      if (k + 1 < order.size()) above = order[k + 1].second;
    }

  // The paper's rule (eq. 6 similarity of the incident slice at t with each neighbour at t+1): the
  // incident slice resembles the side whose sections it will share once the saddle has crossed it.
  const auto incident = polygons_on(seq, f0, slice_id);
  m.similarity_below = below >= 0 ? slice_similarity(incident, polygons_on(seq, f1, below)) : 0.0;
  m.similarity_above = above >= 0 ? slice_similarity(incident, polygons_on(seq, f1, above)) : 0.0;
  VerticalDirection by_similarity = VerticalDirection::None;
  if (std::abs(m.similarity_below - m.similarity_above) > options.tie_tolerance)
    by_similarity = m.similarity_below < m.similarity_above ? VerticalDirection::Up : VerticalDirection::Down;

  // The count rule: the saddle lies, in frame t, between the incident slice and the neighbour that
  // already has the incident slice's next count (the complement); it moves from there across the
  // incident slice. If that does not decide, the neighbour that in frame t+1 still has the
  // incident slice's old count lies in the direction of motion.
  VerticalDirection by_counts = VerticalDirection::None;
  const bool below_t = below >= 0 && count_on(f0, below) == after;
  const bool above_t = above >= 0 && count_on(f0, above) == after;
  if (below_t != above_t) {
    by_counts = below_t ? VerticalDirection::Up : VerticalDirection::Down;
  } else {
    const bool below_t1 = below >= 0 && count_on(f1, below) == before;
    const bool above_t1 = above >= 0 && count_on(f1, above) == before;
    if (below_t1 != above_t1) by_counts = above_t1 ? VerticalDirection::Up : VerticalDirection::Down;
  }

  switch (options.rule) {
    case MotionRule::Counts:
      m.direction = by_counts;
      m.decided_by_counts = true;
      break;
    case MotionRule::Similarity:
      m.direction = by_similarity != VerticalDirection::None ? by_similarity : by_counts;
      m.decided_by_counts = by_similarity == VerticalDirection::None;
      break;
    case MotionRule::Auto:
      m.direction = by_counts != VerticalDirection::None ? by_counts : by_similarity;
      m.decided_by_counts = by_counts != VerticalDirection::None;
      break;
  }
  if (m.direction == VerticalDirection::Up) m.complement_slice = below;
  if (m.direction == VerticalDirection::Down) m.complement_slice = above;
  if (m.complement_slice < 0) m.direction = VerticalDirection::None;
  return m;
}

std::vector<VerticalMotion> vertical_motions(const Sequence& seq, int frame, int next_frame,
                                             const VerticalDeformationOptions& options) {
  check_frames(seq, frame, next_frame);
  std::vector<VerticalMotion> out;
  for (const auto& [offset, id] : slice_order(seq))
    if (count_on(seq.frames[frame], id) != count_on(seq.frames[next_frame], id))
      out.push_back(vertical_motion_direction(seq, frame, next_frame, id, options));
  return out;
}

RidgeEnds ridge_end_points(const std::vector<Vec3>& A, const std::vector<Vec3>& B, const std::vector<Vec3>& C,
                           const Plane& plane, const VerticalDeformationOptions& options) {
  RidgeEnds ends;
  if (A.size() < 3 || B.empty() || C.empty()) return ends;
  std::vector<Vec2> b2, c2;
  for (Vec3 p : B) b2.push_back(to_plane(plane, p));
  for (Vec3 p : C) c2.push_back(to_plane(plane, p));
  const std::size_t n = A.size();
  std::vector<double> diff(n);
  std::vector<char> in(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = to_plane(plane, A[i]);
    const double db = polyline_distance(a, b2, b2.size() > 2), dc = polyline_distance(a, c2, c2.size() > 2);
    diff[i] = std::abs(db - dc);
    in[i] = diff[i] <= options.band * std::max(db, dc) ? 1 : 0;
  }
  // Contiguous runs on the closed contour: start after a point outside the band.
  std::size_t start = n;
  for (std::size_t i = 0; i < n; ++i)
    if (!in[i]) {
      start = i;
      break;
    }
  std::vector<std::vector<int>> bands;
  if (start == n) {
    bands.emplace_back();
    for (std::size_t i = 0; i < n; ++i) bands.back().push_back(static_cast<int>(i));
  } else {
    std::vector<int> run;
    for (std::size_t k = 1; k <= n; ++k) {
      const std::size_t i = (start + k) % n;
      if (in[i]) {
        run.push_back(static_cast<int>(i));
      } else if (!run.empty()) {
        bands.push_back(std::move(run));
        run.clear();
      }
    }
  }
  // Largest first; equal sizes by their smallest index.
  std::stable_sort(bands.begin(), bands.end(), [](const auto& x, const auto& y) {
    if (x.size() != y.size()) return x.size() > y.size();
    return *std::min_element(x.begin(), x.end()) < *std::min_element(y.begin(), y.end());
  });
  for (const auto& b : bands) ends.band_sizes.push_back(static_cast<int>(b.size()));
  if (bands.size() < 2) return ends;
  for (int k = 0; k < 2; ++k) {
    int best = bands[k].front();
    for (int i : bands[k])
      if (diff[i] < diff[best] || (diff[i] == diff[best] && i < best)) best = i;
    ends.index[k] = best;
    ends.points[k] = A[best];
  }
  ends.found = true;
  return ends;
}

std::vector<std::uint32_t> mesh_path(const TriangleMesh& mesh, std::uint32_t from, std::uint32_t to, Vec3 normal,
                                     double h_min, double h_max, RidgePath path, bool* used_shortest) {
  if (used_shortest) *used_shortest = false;
  const std::size_t n = mesh.positions.size();
  if (from >= n || to >= n) return {};
  const auto nb = vertex_neighbours(mesh);
  const auto allowed = [&](std::uint32_t v) {
    if (v == from || v == to) return true;
    const double h = dot(mesh.positions[v], normal);
    return h >= h_min && h <= h_max;
  };
  if (path == RidgePath::Shortest) {
    if (used_shortest) *used_shortest = true;
    return shortest_path(mesh, nb, from, to, allowed);
  }
  // Greedy (the paper): step to the allowed neighbour nearest to the end while that brings us closer.
  const Vec3 target = mesh.positions[to];
  std::vector<std::uint32_t> out{from};
  std::uint32_t cur = from;
  while (cur != to) {
    const double here = distance(mesh.positions[cur], target);
    std::uint32_t best = cur;
    double best_d = here;
    for (std::uint32_t b : nb[cur]) {
      if (!allowed(b)) continue;
      const double d = distance(mesh.positions[b], target);
      if (d < best_d) best_d = d, best = b;
    }
    if (best == cur) {  // stuck in a local minimum: finish along the shortest path
      auto rest = shortest_path(mesh, nb, cur, to, allowed);
      if (rest.empty()) return {};
      if (used_shortest) *used_shortest = true;
      out.insert(out.end(), rest.begin() + 1, rest.end());
      break;
    }
    out.push_back(best);
    cur = best;
  }
  return out;
}

Ridge detect_ridge(const TriangleMesh& mesh, const std::vector<Vec3>& A, const std::vector<Vec3>& B,
                   const std::vector<Vec3>& C, Vec3 normal, const VerticalDeformationOptions& options) {
  Ridge ridge;
  if (mesh.positions.empty() || A.empty()) return ridge;
  const Vec3 nrm = normalized(normal);
  ridge.ends = ridge_end_points(A, B, C, make_plane(A.front(), nrm), options);
  if (!ridge.ends.found) return ridge;
  const double ha = mean_height(A, nrm);
  std::vector<Vec3> bc = B;
  bc.insert(bc.end(), C.begin(), C.end());
  const double hb = mean_height(bc, nrm);
  const double margin = options.slab_margin * std::abs(ha - hb);
  const std::uint32_t from = nearest_vertex(mesh, ridge.ends.points[0]);
  const std::uint32_t to = nearest_vertex(mesh, ridge.ends.points[1]);
  ridge.vertices = mesh_path(mesh, from, to, nrm, std::min(ha, hb) - margin, std::max(ha, hb) + margin, options.path,
                             &ridge.used_shortest_path);
  for (std::uint32_t v : ridge.vertices) ridge.points.push_back(mesh.positions[v]);
  ridge.found = !ridge.vertices.empty();
  return ridge;
}

VerticalField make_vertical_field(const Sequence& seq, const VerticalMotion& motion, const std::vector<Vec3>& ridge,
                                  const std::vector<Vec3>& incident_points, const VerticalDeformationOptions& options) {
  Location where;
  where.file = seq.source;
  where.frame = motion.frame;
  where.slice = motion.incident_slice;
  if (motion.direction == VerticalDirection::None)
    throw InvalidInput(ErrorCode::Internal, where, std::string(__func__) + ": no vertical motion to apply",
                       "call it only for a split or merge whose direction was decided");
  if (ridge.empty() || incident_points.empty())
    throw InvalidInput(ErrorCode::Internal, where, std::string(__func__) + ": empty ridge or incident slice",
                       "detect the ridge first (detect_ridge) and pass the incident slice's points");
  // Slices by decreasing offset (Table 1 counts from the top).
  auto order = slice_order(seq);
  std::reverse(order.begin(), order.end());
  int ki = -1, kc = -1;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (order[k].second == motion.incident_slice) ki = static_cast<int>(k);
    if (order[k].second == motion.complement_slice) kc = static_cast<int>(k);
  }
  if (ki < 0 || kc < 0 || std::abs(ki - kc) != 1)
    throw InvalidInput(ErrorCode::Internal, where,
                       std::string(__func__) + ": incident and complement slices are not neighbours in the stack",
                       "pass a VerticalMotion from vertical_motion_direction on the same sequence");
  const int top = std::min(ki, kc);  // Table 1 position 3
  const double gap = order[top].first - order[top + 1].first;
  VerticalField f;
  f.normal = normalized(seq.normal);
  f.u = seq.u;
  f.v = seq.v;
  f.heights[2] = order[top].first;
  f.heights[3] = order[top + 1].first;
  for (int j = 1; j >= 0; --j) {
    const int k = top - (2 - j);
    f.heights[j] = k >= 0 ? order[k].first : f.heights[j + 1] + gap;
  }
  for (int j = 4; j < 6; ++j) {
    const int k = top + (j - 2);
    f.heights[j] = k < static_cast<int>(order.size()) ? order[k].first : f.heights[j - 1] - gap;
  }
  f.r = motion.direction == VerticalDirection::Up ? options.r_upward : options.r_downward;
  f.delta = options.delta_scale * gap;
  f.taper = options.taper * gap;
  for (Vec3 p : ridge) f.ridge.push_back({dot(p, f.u), dot(p, f.v)});
  for (Vec3 p : incident_points)
    f.lambda = std::max(f.lambda, polyline_distance({dot(p, f.u), dot(p, f.v)}, f.ridge, false));
  return f;
}

double vertical_displacement(const VerticalField& field, Vec3 p) {
  if (!(field.lambda > 0.0) || field.ridge.empty()) return 0.0;
  const double d = polyline_distance({dot(p, field.u), dot(p, field.v)}, field.ridge, false);
  if (d >= field.lambda) return 0.0;
  const double r = r_at(field, dot(p, field.normal));
  return field.delta * (r / 2.0) * (std::sin(std::numbers::pi * (2.0 * d + field.lambda) / (2.0 * field.lambda)) + 1.0);
}

void apply_vertical_deformation(std::vector<Vec3>& positions, const VerticalField& field) {
  for (Vec3& p : positions) p += vertical_displacement(field, p) * field.normal;
}

}  // namespace c4d
