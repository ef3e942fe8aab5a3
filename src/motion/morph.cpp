// Lim et al. 2014, "4D Morphing of the Heart Model" and "Contour Matching" (Fig. 7); Miara et al.
// §III.E (sub-mesh lifetimes, Fig. 14).
//
// Per frame t, the previous mesh is cut by every slice plane; each section loop that matches one
// contour of frame t one-to-one (similarity index over the threshold both ways) is mapped onto it
// (contour matching) and the matched points drive a Hardy-multiquadric RBF (eq. 9) that moves the
// whole mesh. Slices whose contours split, merge, appear or vanish give no constraint; they are
// reported as events. The paper resolves them with a sine-shaped vertical pre-deformation; our
// default instead projects the mesh onto frame t's own surface (reconstructed from its contours,
// branching included), with a Laplacian term that keeps the previous frame's shape (Sorkine et al.,
// "Laplacian Surface Editing", 2004) — its matrix depends only on the connectivity, so it is
// factored once for the whole sequence — followed by tangential relaxation that keeps triangle
// quality (vertices move within the surface, so the contours stay on it).
// With MorphOptions::biharmonic, a frame that keeps the previous frame's contour topology is instead the
// previous mesh plus one thin-plate (biharmonic) displacement that puts its slice sections on the new
// contours (the "global Laplacian solve whose factorisation is reused"), guarded by the quality checks.
#include "contour4d/motion/morph.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <set>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include "contour4d/connect/similarity.h"
#include "contour4d/core/errors.h"
#include "contour4d/core/packed_math.h"
#include "contour4d/core/sparse_solve.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/motion/contour_fit.h"
#include "contour4d/motion/contour_matching.h"
#include "contour4d/motion/corner_snap.h"
#include "contour4d/motion/rbf.h"
#include "contour4d/motion/section.h"
#include "contour4d/motion/vertical_deformation.h"
#include "contour4d/surface/angle_repair.h"
#include "contour4d/motion/chains.h"
#include "contour4d/metrics/surface_projector.h"
#include "simd_avx_internal.h"
#include "sweep_lanes_internal.h"

namespace c4d {
namespace {

// Vertices per relaxation sweep step (MorphOptions::sweep_lanes): 0 the widest this CPU runs (4 with
// AVX, else 2 with SSE2), else the request limited to that; 1 without SSE2.
int sweep_width(int requested) {
#if defined(__SSE2__)
  static const bool quad = detail::avx_available();
  const int widest = quad ? 4 : 2;
  if (requested <= 0) return widest;
  return requested >= 4 ? widest : (requested >= 2 ? 2 : 1);
#else
  (void)requested;
  return 1;
#endif
}

using SparseMatrix = Eigen::SparseMatrix<double>;

// Uniform ("umbrella") Laplacian: (L x)_i = x_i − mean of the neighbours of i.
SparseMatrix uniform_laplacian(const std::vector<std::vector<std::uint32_t>>& nb) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t i = 0; i < nb.size(); ++i) {
    const auto I = static_cast<int>(i);
    t.emplace_back(I, I, 1.0);
    for (std::uint32_t j : nb[i]) t.emplace_back(I, static_cast<int>(j), -1.0 / static_cast<double>(nb[i].size()));
  }
  SparseMatrix L(static_cast<int>(nb.size()), static_cast<int>(nb.size()));
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

Eigen::MatrixXd to_matrix(const std::vector<Vec3>& p) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(p.size()), 3);
  for (std::size_t i = 0; i < p.size(); ++i) m.row(static_cast<Eigen::Index>(i)) << p[i].x, p[i].y, p[i].z;
  return m;
}

std::vector<Vec3> from_matrix(const Eigen::MatrixXd& m) {
  std::vector<Vec3> p(static_cast<std::size_t>(m.rows()));
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto I = static_cast<Eigen::Index>(i);
    p[i] = {m(I, 0), m(I, 1), m(I, 2)};
  }
  return p;
}

std::vector<Vec2> flatten(const Plane& pl, const std::vector<Vec3>& pts) {
  std::vector<Vec2> out;
  out.reserve(pts.size());
  for (const Vec3& p : pts) out.push_back(to_plane(pl, p));
  return out;
}

const Slice* find_slice(const Frame& f, int id) {
  for (const Slice& s : f.slices)
    if (s.id == id) return &s;
  return nullptr;
}

// Every contour of a frame, as closed polylines (mm).
std::vector<std::vector<Vec3>> frame_contours(const Frame& f) {
  std::vector<std::vector<Vec3>> out;
  for (const Slice& s : f.slices)
    for (const Contour& c : s.contours) out.push_back(c.points);
  return out;
}

std::string event_kind(int before, int after) {
  if (before == 0) return "appear";
  if (after == 0) return "vanish";
  if (before == 1 && after > 1) return "split";
  if (before > 1 && after == 1) return "merge";
  return "change";
}

struct ChainTarget {
  std::uint32_t vertex;
  Vec3 position;
  bool pinned;  // held there by the projection and relaxation, not only guided by the RBF
  int line;     // >= 0: slides along this matched contour (index into the frame's contour lines)
  int slice;    // slice id of the chain
};

// Chain vertices at least `spacing` apart along a contour of `length` carrying `count` of them: every
// stride-th one (0: none).
std::size_t spacing_stride(double spacing, double length, std::size_t count) {
  const double per = length / static_cast<double>(std::max<std::size_t>(1, count));
  const double ratio = per > 0 ? spacing / per : 1.0;
  return (spacing <= 0 || ratio > 1e6) ? 0 : std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(ratio - 1e-9)));
}

bool on_stride(std::size_t k, std::size_t stride, std::size_t count) {
  return stride > 0 && k % stride == 0 && (stride == 1 || k + stride / 2 < count);
}

// Matches the chains (at their current positions) to the contours of `frame`, one-to-one per slice;
// fills `target` for every vertex of a matched chain and `lines` with the matched contours. Reports
// slices whose contour count changed; `unmatched` gets them, those changing into the next frame, and
// those with a chain left without partner.
void match_chains(const Sequence& seq, const std::vector<Chain>& chains, const std::vector<Vec3>& x, int frame,
                  const MorphOptions& opt, double pin_spacing, double slide_spacing, std::vector<ChainTarget>& targets,
                  std::vector<std::vector<Vec3>>& lines, std::set<int>& unmatched, MorphFrameReport& fr,
                  std::vector<SliceEvent>& events, std::map<int, int>& previous_counts) {
  std::map<int, std::vector<std::size_t>> by_slice;
  for (std::size_t c = 0; c < chains.size(); ++c) by_slice[chains[c].slice].push_back(c);
  const Frame& target = seq.frames[static_cast<std::size_t>(frame)];
  std::map<int, int> counts;
  for (const Slice& s : target.slices) counts[s.id] = static_cast<int>(s.contours.size());
  for (const auto& [id, n] : counts)
    if (previous_counts[id] != n) {
      events.push_back({frame, id, event_kind(previous_counts[id], n), previous_counts[id], n});
      unmatched.insert(id);
    }
  for (const auto& [id, n] : previous_counts)
    if (n > 0 && !counts.count(id)) events.push_back({frame, id, "vanish", n, 0});
  if (static_cast<std::size_t>(frame) + 1 < seq.frames.size()) {
    std::map<int, int> next;
    for (const Slice& s : seq.frames[static_cast<std::size_t>(frame) + 1].slices) next[s.id] = static_cast<int>(s.contours.size());
    for (const auto& [id, n] : counts)
      if (next[id] != n) unmatched.insert(id);
  }
  previous_counts = counts;

  for (const auto& [id, idx] : by_slice) {
    const Slice* ts = find_slice(target, id);
    if (!ts) {
      unmatched.insert(id);
      continue;
    }
    const Plane& pl = chains[idx.front()].plane;
    std::vector<std::vector<Vec2>> a, b;
    for (std::size_t c : idx) {
      std::vector<Vec3> pts;
      for (std::uint32_t v : chains[c].loop) pts.push_back(x[v]);
      a.push_back(flatten(pl, pts));
    }
    for (const Contour& c : ts->contours) b.push_back(flatten(pl, c.points));
    std::vector<std::vector<double>> sim(a.size(), std::vector<double>(b.size()));
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t j = 0; j < b.size(); ++j) sim[i][j] = contour_similarity(a[i], b[j]);
    for (std::size_t i = 0; i < a.size(); ++i) {
      const int partner = one_to_one_partner(sim, i, opt.threshold);
      if (partner < 0) {
        unmatched.insert(id);
        continue;
      }
      const ContourMatch m = match_contour(a[i], b[static_cast<std::size_t>(partner)]);
      const Chain& ch = chains[idx[i]];
      // Every chain vertex gets a target (they all guide the RBF). A contour that shrank would crowd
      // its chain if all were held there: only every stride-th vertex is pinned, so pinned points
      // stay about pin_spacing apart and the others relax on the surface.
      // Likewise, only chain vertices slide_spacing apart slide along the contour.
      double len = 0;
      for (std::size_t k = 0; k < m.targets.size(); ++k) len += norm(m.targets[(k + 1) % m.targets.size()] - m.targets[k]);
      const std::size_t stride = spacing_stride(pin_spacing, len, ch.loop.size());
      const std::size_t slide = spacing_stride(slide_spacing, len, ch.loop.size());
      const int line = static_cast<int>(lines.size());
      lines.push_back(ts->contours[static_cast<std::size_t>(partner)].points);
      for (std::size_t k = 0; k < ch.loop.size(); ++k)
        targets.push_back({ch.loop[k], from_plane(pl, m.targets[k]), on_stride(k, stride, ch.loop.size()),
                           on_stride(k, slide, ch.loop.size()) ? line : -1, id});
      ++fr.matched;
    }
  }
}

// Area of the triangles of (pos, tris) per band between consecutive slice heights (band 0 below the
// first height, band n above the last), each triangle counted in the band of its centroid.
std::vector<double> band_areas(const std::vector<Vec3>& pos, const std::vector<Triangle>& tris, Vec3 normal,
                               const std::vector<double>& heights) {
  std::vector<double> a(heights.size() + 1, 0.0);
  for (const Triangle& t : tris) {
    const Vec3 p = pos[t[0]], q = pos[t[1]], r = pos[t[2]];
    const double h = dot(p + q + r, normal) / 3.0;
    const auto b = static_cast<std::size_t>(std::upper_bound(heights.begin(), heights.end(), h) - heights.begin());
    a[b] += 0.5 * norm(cross(q - p, r - p));
  }
  return a;
}

// Summed contour perimeter per slice id of one frame.
std::map<int, double> slice_perimeters(const Frame& f) {
  std::map<int, double> out;
  for (const Slice& s : f.slices)
    for (const Contour& c : s.contours)
      for (std::size_t k = 0; k < c.points.size(); ++k)
        out[s.id] += distance(c.points[k], c.points[(k + 1) % c.points.size()]);
  return out;
}

// Frame 0's bands between the slices that carry contour chains.
struct Bands {
  std::vector<double> heights;  // slice heights along the stack normal, ascending
  std::vector<int> slice_ids;   // the slices at those heights
  std::vector<double> areas;    // band_areas of frame 0's mesh
  std::map<int, double> perimeters;  // slice_perimeters of frame 0
  std::map<int, std::size_t> counts;  // contours per slice id of frame 0
};

// Next to a slice whose contours split, merge, appear or vanish (`unmatched`), the surface must move
// through the slices to follow: chains there and on the slices beside it are held (in their planes,
// they would crowd the triangles).
void hold_next_to(const Bands& b0, const std::set<int>& unmatched, std::set<int>& held) {
  held.insert(unmatched.begin(), unmatched.end());
  const std::vector<int>& ids = b0.slice_ids;
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (unmatched.count(ids[k])) {
      if (k > 0) held.insert(ids[k - 1]);
      if (k + 1 < ids.size()) held.insert(ids[k + 1]);
    }
}

// MorphOptions::saddle_curvature: the height ranges (along the stack normal) of the bands beside each slice
// whose contour count in frame t differs from frame 0's, both non-zero (split or merged contours: the
// surface forms a saddle there that frame 0's vertex density does not follow).
std::vector<std::pair<double, double>> saddle_bands(const Sequence& seq, const Bands& b0, int t) {
  std::vector<std::pair<double, double>> out;
  const std::vector<int>& ids = b0.slice_ids;
  for (const Slice& s : seq.frames[static_cast<std::size_t>(t)].slices) {
    const auto it = b0.counts.find(s.id);
    if (it == b0.counts.end() || it->second == 0 || s.contours.empty() || it->second == s.contours.size()) continue;
    const auto k = static_cast<std::size_t>(std::find(ids.begin(), ids.end(), s.id) - ids.begin());
    if (k == ids.size()) continue;
    const double lo = k > 0 ? b0.heights[k - 1] : -std::numeric_limits<double>::infinity();
    const double hi = k + 1 < ids.size() ? b0.heights[k + 1] : std::numeric_limits<double>::infinity();
    out.push_back({lo, hi});
  }
  return out;
}

// A chain sliding in its plane fixes how many vertices the bands beside it hold. Where a band changed
// shape unevenly since frame 0 (its height, from its area on the frame's own surface over its width,
// scaled more than `limit` × its width, the contours' perimeter ratio, or the reverse), those vertices
// must move through the plane to keep their triangles: the chains bounding it are held.
void hold_uneven_bands(const Bands& b0, const TriangleMesh& surface, const Frame& frame, Vec3 normal, double limit,
                       std::set<int>& held) {
  const std::vector<double> at = band_areas(surface.positions, surface.triangles, normal, b0.heights);
  const std::map<int, double> pt = slice_perimeters(frame);
  const std::size_t n = b0.heights.size();
  auto ratio = [&](std::size_t k) {
    const auto p = b0.perimeters.find(b0.slice_ids[k]), q = pt.find(b0.slice_ids[k]);
    return p == b0.perimeters.end() || q == pt.end() || p->second <= 0 ? -1.0 : q->second / p->second;
  };
  for (std::size_t b = 0; b <= n; ++b) {
    double sum = 0;
    int count = 0;
    bool uneven = false;
    for (std::size_t k : {b - 1, b}) {
      if (k >= n) continue;  // b - 1 wraps for b = 0
      const double r = ratio(k);
      if (r <= 0) uneven = true;  // a contour gone
      sum += r;
      ++count;
    }
    if (!uneven && count > 0 && b0.areas[b] > 0 && at[b] > 0) {
      const double width = sum / count, height = at[b] / b0.areas[b] / width;
      uneven = height > limit * width || width > limit * height;
    }
    if (!uneven) continue;
    if (b > 0) held.insert(b0.slice_ids[b - 1]);
    if (b < n) held.insert(b0.slice_ids[b]);
  }
}

// MorphOptions::plane_snap's candidates: on every mesh edge (rings in CSR form) that crosses the plane of
// one of `lines` within `reach` of that line, the endpoint nearer the plane. Per vertex: the line of its
// nearest such crossing, -1 for none.
std::vector<std::int32_t> nearest_to_planes(const std::vector<Vec3>& x, const std::vector<std::size_t>& ring_start,
                                            const std::vector<std::uint32_t>& ring_index,
                                            const std::vector<std::vector<Vec3>>& lines, Vec3 normal, double reach) {
  const std::size_t nv = x.size();
  std::vector<double> line_h(lines.size());
  for (std::size_t l = 0; l < lines.size(); ++l) line_h[l] = dot(lines[l].front(), normal);
  // Whether a contour passes within `reach` of a point, as distance(closest_on_loop(...)) <= reach
  // but faster: the contour's segments in runs of 16 with their bounding boxes, boxes farther than
  // reach (with a margin well above rounding) skipped, and the first segment within reach ends it.
  constexpr std::size_t kRun = 16;
  std::vector<std::vector<std::array<Vec3, 2>>> boxes(lines.size());
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const std::vector<Vec3>& L = lines[l];
    for (std::size_t k0 = 0; k0 < L.size(); k0 += kRun) {
      Vec3 lo = L[k0], hi = L[k0];
      for (std::size_t k = k0; k <= std::min(k0 + kRun, L.size()); ++k) {
        const Vec3 p = L[k % L.size()];
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
      }
      boxes[l].push_back({lo, hi});
    }
  }
  const double margin = 1e-6 * (1.0 + reach);
  auto within = [&](std::size_t l, Vec3 q) {
    const std::vector<Vec3>& L = lines[l];
    const std::size_t n = L.size();
    for (std::size_t b = 0; b < boxes[l].size(); ++b) {
      const auto& [lo, hi] = boxes[l][b];
      const Vec3 d{std::max({lo.x - q.x, 0.0, q.x - hi.x}), std::max({lo.y - q.y, 0.0, q.y - hi.y}),
                   std::max({lo.z - q.z, 0.0, q.z - hi.z})};
      if (norm(d) > reach + margin) continue;
      for (std::size_t k = b * kRun; k < std::min(n, (b + 1) * kRun); ++k)
        if (distance(closest_on_segment(L[k], L[(k + 1) % n], q), q) <= reach) return true;
    }
    return false;
  };
  // The edges' crossings in parallel, in fixed blocks of vertices, each block listing its candidates in
  // the serial loop's order; then each vertex keeps the first candidate with the smallest gap, the
  // blocks taken in order: the same choice as one loop over the vertices, at any thread count.
  struct Candidate {
    std::uint32_t vertex;
    std::int32_t line;
    double gap;
  };
  constexpr std::size_t kBlock = 1024;
  std::vector<std::vector<Candidate>> found((nv + kBlock - 1) / kBlock);
  // An edge crosses (or touches) line l's plane exactly when line_h[l] lies between its ends' heights
  // (di and dj below are then of opposite signs or zero): the sorted heights tell at once whether any
  // does, and most edges cross none.
  std::vector<double> heights = line_h;
  std::sort(heights.begin(), heights.end());
  tbb::parallel_for(std::size_t(0), found.size(), [&](std::size_t b) {
    for (std::size_t i = b * kBlock; i < std::min(nv, (b + 1) * kBlock); ++i) {
      const double hi = dot(x[i], normal);
      for (std::size_t r = ring_start[i]; r < ring_start[i + 1]; ++r) {
        const std::uint32_t j = ring_index[r];
        if (j <= i) continue;
        const double hj = dot(x[j], normal);
        const auto first = std::lower_bound(heights.begin(), heights.end(), std::min(hi, hj));
        if (first == heights.end() || *first > std::max(hi, hj)) continue;
        for (std::size_t l = 0; l < lines.size(); ++l) {
          const double di = hi - line_h[l], dj = hj - line_h[l];
          if ((di > 0) == (dj > 0) && di != 0 && dj != 0) continue;
          const std::size_t v = std::abs(di) <= std::abs(dj) ? i : j;
          const double gap = std::abs(v == i ? di : dj);
          // Which contour of the slice: the one nearest the crossing.
          const double s = di == dj ? 0.5 : di / (di - dj);
          const Vec3 c = x[i] + s * (x[j] - x[i]);
          if (within(l, c)) found[b].push_back({static_cast<std::uint32_t>(v), static_cast<std::int32_t>(l), gap});
        }
      }
    }
  });
  std::vector<std::int32_t> best_line(nv, -1);
  std::vector<double> best_gap(nv, std::numeric_limits<double>::infinity());
  for (const std::vector<Candidate>& block : found)
    for (const Candidate& c : block)
      if (c.gap < best_gap[c.vertex]) {
        best_gap[c.vertex] = c.gap;
        best_line[c.vertex] = c.line;
      }
  return best_line;
}

// What decides whether a frame is redone, and which of two tries is kept.
struct FrameQuality {
  std::size_t crossings = 0;  // intersecting triangle pairs left
  double worst = 0;           // smallest angle (degrees)
  double good = 0;            // share of angles in 40–80°
};

FrameQuality frame_quality(const std::vector<Vec3>& x, const std::vector<Triangle>& tris, std::size_t crossings) {
  const AngleQuality q = angle_quality(TriangleMesh{x, tris});
  return {crossings, q.min_angle_deg, q.pct_40_80 / 100.0};
}

// A frame needs no retry (and a biharmonic frame is kept): no crossings, no angle below retry_min_angle_deg,
// at least retry_min_good_share of its angles in 40–80°.
bool acceptable(const FrameQuality& q, const MorphOptions& opt) {
  return q.crossings == 0 && q.worst >= opt.retry_min_angle_deg && q.good >= opt.retry_min_good_share;
}

// Marks `mark` and `rings` rings of neighbours around the marked vertices (rings in CSR form).
void grow(std::vector<char>& mark, const std::vector<std::size_t>& ring_start, const std::vector<std::uint32_t>& ring_index,
          int rings) {
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> grown = mark;
    for (std::size_t v = 0; v < mark.size(); ++v)
      if (mark[v])
        for (std::size_t r = ring_start[v]; r < ring_start[v + 1]; ++r) grown[ring_index[r]] = 1;
    mark.swap(grown);
  }
}

// Vertices of the triangles of `after` whose smallest angle fell below min(its angle in `before`,
// floor_deg); true if any.
bool mark_lost_angles(const std::vector<Vec3>& before, const std::vector<Vec3>& after, const std::vector<Triangle>& tris,
                      double floor_deg, std::vector<char>& mark) {
  bool any = false;
  for (const Triangle& tri : tris) {
    const double a = min_angle_deg(after[tri[0]], after[tri[1]], after[tri[2]]);
    if (a >= floor_deg || a >= min_angle_deg(before[tri[0]], before[tri[1]], before[tri[2]]) - 1e-9) continue;
    any = true;
    for (std::uint32_t v : tri) mark[v] = 1;
  }
  return any;
}

// MorphOptions::contour_fit: fit_to_points on the contour samples, kept only where it harms nothing. Where the fit leaves a
// triangle's smallest angle below min(its angle before, floor_deg), the vertices there (and a ring)
// move within the fitted surface to raise it (repair_small_angles) and then stay while the fit is done
// again around them. Where triangles still lose angles, or more triangles cross than before, those
// vertices and two rings around them stay at their place before the fit and it is done again. Up to
// four rounds; if no fit is harmless, x stays as it was.
ContourFitReport guarded_contour_fit(std::vector<Vec3>& x, const std::vector<Triangle>& tris,
                                     const std::vector<Vec3>& samples, std::vector<char> fixed,
                                     const std::vector<std::size_t>& ring_start, const std::vector<std::uint32_t>& ring_index,
                                     double repair_below_deg, double floor_deg, const AngleRepairOptions& repair,
                                     const ContourFitOptions& options) {
  // Each call's closest points start the next call's search (the meshes differ only near the far samples).
  std::vector<std::int32_t> sample_triangles;
  auto largest_distance = [&](const std::vector<Vec3>& positions) {
    ContourFitOptions measure = options;
    measure.iterations = 0;
    std::vector<Vec3> probe = positions;
    return fit_to_points(probe, tris, samples, fixed, measure, &sample_triangles).max_before_mm;
  };
  ContourFitReport rep;
  std::vector<Vec3> start = x;  // what each round fits from
  std::vector<Vec3> harmless;   // the last harmless result
  for (int round = 0; round < 4; ++round) {
    std::vector<Vec3> fitted = start;
    const ContourFitReport cf = fit_to_points(fitted, tris, samples, fixed, options, &sample_triangles);
    if (round == 0) rep.max_before_mm = rep.max_after_mm = cf.max_before_mm;
    if (cf.moved == 0) break;
    std::vector<char> bad(x.size(), 0), repaired(x.size(), 0);
    if (mark_lost_angles(x, fitted, tris, repair_below_deg, bad)) {
      // The repair is kept where the fit left an angle below floor_deg, or where it keeps the fit's
      // largest contour distance (it moves vertices within the piecewise-flat surface, which can cut
      // across a contour again).
      std::vector<char> frozen(x.size(), 1), near = bad;
      grow(near, ring_start, ring_index, 1);
      for (std::size_t v = 0; v < x.size(); ++v)
        if (near[v]) frozen[v] = fixed[v];
      std::vector<Vec3> mended = fitted;
      const SurfaceProjector surface(TriangleMesh{fitted, tris});
      AngleRepairOptions local = repair;
      local.target_deg = std::max(local.target_deg, repair_below_deg);
      repair_small_angles(mended, tris, frozen, [&](std::uint32_t, Vec3 p) { return surface.closest(p); }, local);
      std::vector<char> below_floor(x.size(), 0);
      if (mark_lost_angles(x, fitted, tris, floor_deg, below_floor) ||
          largest_distance(mended) <= cf.max_after_mm + options.tolerance_mm) {
        fitted = std::move(mended);
        repaired = std::move(near);
      }
      std::fill(bad.begin(), bad.end(), 0);
      mark_lost_angles(x, fitted, tris, floor_deg, bad);
    }
    // Crossings: only pairs with a triangle that moved can have changed.
    std::vector<char> touched(tris.size(), 0);
    for (std::size_t f = 0; f < tris.size(); ++f)
      for (std::uint32_t v : tris[f]) touched[f] |= !(fitted[v] == x[v]);
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    if (count_self_intersections_of(TriangleMesh{fitted, tris}, touched, &pairs, tris.size()) >
        count_self_intersections_of(TriangleMesh{x, tris}, touched))
      for (const auto& [a, b] : pairs)
        for (std::size_t f : {a, b})
          for (std::uint32_t v : tris[f]) bad[v] = 1;
    if (std::find(bad.begin(), bad.end(), 1) == bad.end()) {
      harmless = fitted;
      if (std::find(repaired.begin(), repaired.end(), 1) == repaired.end()) break;
      start = std::move(fitted);  // fit again around the repaired vertices, which stay
      for (std::size_t v = 0; v < x.size(); ++v)
        if (repaired[v]) fixed[v] = 1;
      continue;
    }
    grow(bad, ring_start, ring_index, 2);
    for (std::size_t v = 0; v < x.size(); ++v)
      if (bad[v]) {
        fixed[v] = 1;
        start[v] = x[v];
      }
  }
  if (harmless.empty()) return rep;
  for (std::size_t v = 0; v < x.size(); ++v) rep.moved += !(harmless[v] == x[v]);
  x = std::move(harmless);
  rep.max_after_mm = largest_distance(x);
  return rep;
}

// a better than b: fewer crossings; then above the angle floor; then the larger smallest angle below it,
// or the larger share of good angles above it.
bool better(const FrameQuality& a, const FrameQuality& b, double floor_deg) {
  if (a.crossings != b.crossings) return a.crossings < b.crossings;
  const bool fa = a.worst >= floor_deg, fb = b.worst >= floor_deg;
  if (fa != fb) return fa;
  return fa ? a.good > b.good : a.worst > b.worst;
}

// Adds the vertex farthest from the sources' plane as a fixed point when all sources are coplanar
// (the paper's "far point"), so the RBF system stays regular.
void add_far_point(const std::vector<Vec3>& verts, const Vec3& normal, std::vector<Vec3>& src, std::vector<Vec3>& dst) {
  if (src.empty()) return;
  double lo = 1e300, hi = -1e300;
  for (const Vec3& p : src) {
    lo = std::min(lo, dot(p, normal));
    hi = std::max(hi, dot(p, normal));
  }
  if (hi - lo > 1e-6) return;
  std::size_t best = 0;
  double far = -1;
  for (std::size_t i = 0; i < verts.size(); ++i) {
    const double d = std::abs(dot(verts[i], normal) - lo);
    if (d > far) {
      far = d;
      best = i;
    }
  }
  src.push_back(verts[best]);
  dst.push_back(verts[best]);
}

// Projection of all vertices onto one frame's surface; each vertex remembers the triangle it last
// landed on and starts its next search there (the vertices move little between passes). The hint
// only narrows the search, so the result does not depend on the thread count.
// The vertices are visited in `order` (when given, a permutation of them): consecutive queries then
// fall on nearby parts of the tree. Each vertex's answer depends on its own query and hint only.
struct Projector {
  const SurfaceProjector& surface;
  mutable std::vector<std::int32_t> hints;
  const std::vector<std::uint32_t>* order = nullptr;
  std::vector<Vec3> project(const std::vector<Vec3>& x, std::vector<Vec3>* normals = nullptr) const {
    std::vector<Vec3> p(x.size());
    if (normals) normals->resize(x.size());
    hints.resize(x.size(), -1);
    const bool ordered = order != nullptr && order->size() == x.size();
    tbb::parallel_for(std::size_t(0), x.size(), [&](std::size_t k) {
      const std::size_t i = ordered ? (*order)[k] : k;
      p[i] = surface.walk(x[i], normals ? &(*normals)[i] : nullptr, &hints[i]);
    });
    return p;
  }
};

// The vertices in breadth-first order over the mesh's edges (each component from its lowest vertex;
// neighbours in ring order): new position → vertex. Neighbours get nearby positions.
std::vector<std::uint32_t> breadth_first_order(const std::vector<std::size_t>& ring_start,
                                               const std::vector<std::uint32_t>& ring_index) {
  const std::size_t nv = ring_start.size() - 1;
  std::vector<std::uint32_t> order;
  order.reserve(nv);
  std::vector<char> seen(nv, 0);
  for (std::size_t s = 0; s < nv; ++s) {
    if (seen[s]) continue;
    seen[s] = 1;
    std::size_t k = order.size();
    order.push_back(static_cast<std::uint32_t>(s));
    for (; k < order.size(); ++k) {
      const std::uint32_t v = order[k];
      for (std::size_t r = ring_start[v]; r < ring_start[v + 1]; ++r)
        if (!seen[ring_index[r]]) {
          seen[ring_index[r]] = 1;
          order.push_back(ring_index[r]);
        }
    }
  }
  return order;
}

// Lim et al. 2014, "2D contour topological changes": where a slice's contours split or merge between
// frames t−1 and t, the mesh (at frame t−1) is first moved along the stack normal by the sine field
// centred on the ridge, so that its section at the incident slice has frame t's contour count and
// the matching below finds one-to-one partners there.
void vertical_predeformation(const Sequence& seq, const std::vector<Triangle>& triangles, int t, const MorphOptions& opt,
                             std::vector<Vec3>& x) {
  for (const VerticalMotion& m : vertical_motions(seq, t - 1, t, opt.vertical)) {
    if (m.direction == VerticalDirection::None) continue;
    const Frame& before = seq.frames[static_cast<std::size_t>(t - 1)];
    const Slice* incident = find_slice(before, m.incident_slice);
    const Slice* complement = find_slice(before, m.complement_slice);
    if (!incident || !complement) continue;
    const TriangleMesh current{x, triangles};
    const auto inc = plane_section(current, slice_plane(seq, *incident));
    const auto comp = plane_section(current, slice_plane(seq, *complement));
    const auto& lone = inc.size() == 1 ? inc : comp;
    const auto& pair = inc.size() == 1 ? comp : inc;
    if (lone.size() != 1 || pair.size() != 2) continue;  // not the 1↔2 case the paper describes
    const Ridge ridge = detect_ridge(current, lone[0], pair[0], pair[1], seq.normal, opt.vertical);
    if (!ridge.found) continue;
    std::vector<Vec3> incident_points;
    for (const auto& loop : inc) incident_points.insert(incident_points.end(), loop.begin(), loop.end());
    apply_vertical_deformation(x, make_vertical_field(seq, m, ridge.points, incident_points, opt.vertical));
  }
}

// MorphOptions::biharmonic. Where every slice keeps frame t−1's contours (the same count, each matched
// one-to-one by the similarity index), the mesh's section on each slice plane (the points where its edges
// cross it) is mapped onto frame t's contours: each section point goes to its closest point on frame t−1's
// contour and on through that contour's match onto frame t's (Fig. 7). The displacement d then minimises
// Σ|L d|² + w Σ_k |(1 − s_k) d_a + s_k d_b − δ_k|² (the section point k on edge (a, b) at s_k, δ_k its
// move): smooth over the whole mesh, the sections onto the new contours. A frame whose sections cut the same
// edges at the same parameters as the last factorised one's (sections through chain vertices that stayed on
// their planes) reuses its factorisation; any other frame costs one.
struct BiharmonicStep {
  SparseLdlt solver;  // SimplicialLDLT's factor bit for bit, factored faster (sparse_solve.h)
  std::vector<double> factored_for;  // the constraints' (a, b, s) of the factorised system
  double weight = 1e4;  // w, against LᵀL's diagonal of about 40

  // y = x + d; false (y untouched) when a slice does not qualify or the system fails.
  bool run(const Sequence& seq, int t, const std::vector<Vec3>& x, const std::vector<std::array<std::uint32_t, 2>>& edges,
           const SparseMatrix& LtL, double threshold, std::vector<Vec3>& y) {
    const Frame& prev = seq.frames[static_cast<std::size_t>(t - 1)];
    const Frame& cur = seq.frames[static_cast<std::size_t>(t)];
    if (prev.slices.size() != cur.slices.size()) return false;
    struct Constraint {
      std::uint32_t a, b;
      double s;
      Vec3 delta;
    };
    std::vector<Constraint> cons;
    std::vector<double> h(x.size());
    for (const Slice& ps : prev.slices) {
      const Slice* cs = find_slice(cur, ps.id);
      if (!cs || cs->contours.size() != ps.contours.size() || ps.contours.empty()) return false;
      const Plane pl = slice_plane(seq, ps);
      std::vector<std::vector<Vec2>> A, B;
      for (const Contour& c : ps.contours) A.push_back(flatten(pl, c.points));
      for (const Contour& c : cs->contours) B.push_back(flatten(pl, c.points));
      std::vector<std::vector<double>> sim(A.size(), std::vector<double>(B.size()));
      for (std::size_t i = 0; i < A.size(); ++i)
        for (std::size_t j = 0; j < B.size(); ++j) sim[i][j] = contour_similarity(A[i], B[j]);
      std::vector<ContourMatch> maps(A.size());
      for (std::size_t i = 0; i < A.size(); ++i) {
        const int partner = one_to_one_partner(sim, i, threshold);
        if (partner < 0) return false;
        maps[i] = match_contour(A[i], B[static_cast<std::size_t>(partner)]);
        if (maps[i].targets.size() != A[i].size()) return false;
      }
      // Vertices within 1e-9 mm of the plane lie on it (frame 0's contour chains): each is one section point.
      // Otherwise, each edge with its ends on either side gives one.
      for (std::size_t v = 0; v < x.size(); ++v) {
        h[v] = dot(x[v] - pl.origin, pl.normal);
        if (std::abs(h[v]) <= 1e-9) h[v] = 0;
      }
      const std::size_t before = cons.size();
      std::vector<std::array<std::uint32_t, 2>> crossing;
      for (std::size_t v = 0; v < x.size(); ++v)
        if (h[v] == 0) crossing.push_back({static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(v)});
      for (const auto& e : edges)
        if ((h[e[0]] > 0 && h[e[1]] < 0) || (h[e[0]] < 0 && h[e[1]] > 0)) crossing.push_back(e);
      for (const auto& [a, b] : crossing) {
        const double s = a == b ? 0.0 : h[a] / (h[a] - h[b]);
        const Vec3 p = x[a] + s * (x[b] - x[a]);
        double best = std::numeric_limits<double>::infinity();
        std::size_t bc = 0, bk = 0;
        Vec3 bq = p;
        for (std::size_t c = 0; c < ps.contours.size(); ++c) {
          std::int32_t k = -1;
          const Vec3 q = closest_on_loop(ps.contours[c].points, p, k);
          if (const double d = distance(p, q); d < best) best = d, bc = c, bk = static_cast<std::size_t>(k), bq = q;
        }
        if (!(best < 1.0)) return false;  // the section is not on frame t−1's contours
        const std::vector<Vec3>& L = ps.contours[bc].points;
        const Vec3 e = L[(bk + 1) % L.size()] - L[bk];
        const double f = dot(e, e) > 0 ? dot(bq - L[bk], e) / dot(e, e) : 0.0;
        const Vec2 target = target_between(maps[bc], bk, f);
        cons.push_back({a, b, s, from_plane(pl, target) - p});
      }
      if (cons.size() == before) return false;
    }
    // The system depends on the section's edges and their parameters only: where they are those of the last
    // factorised frame (sections through vertices on the planes, which stay there), it is reused.
    std::vector<double> signature;
    for (const Constraint& c : cons) signature.insert(signature.end(), {double(c.a), double(c.b), c.s});
    const bool refactor = factored_for.empty() || signature != factored_for;
    SparseMatrix M;
    if (refactor) M = LtL;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(x.size()), 3);
    for (const Constraint& c : cons) {
      const double wa = 1.0 - c.s, wb = c.s;
      const int ia = static_cast<int>(c.a), ib = static_cast<int>(c.b);
      if (refactor) {
        M.coeffRef(ia, ia) += weight * wa * wa;
        if (ia != ib) {
          M.coeffRef(ib, ib) += weight * wb * wb;
          M.coeffRef(ia, ib) += weight * wa * wb;
          M.coeffRef(ib, ia) += weight * wa * wb;
        }
      }
      for (int k = 0; k < 3; ++k) {
        const double dk = k == 0 ? c.delta.x : k == 1 ? c.delta.y : c.delta.z;
        rhs(ia, k) += weight * wa * dk;
        if (ia != ib) rhs(ib, k) += weight * wb * dk;
      }
    }
    if (refactor) {
      if (!factor_lower(solver, M)) {
        factored_for.clear();
        return false;
      }
      factored_for = signature;
    }
    const Eigen::MatrixXd d = ldlt_solve(solver, rhs);
    y.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      y[i] = x[i] + Vec3{d(r, 0), d(r, 1), d(r, 2)};
    }
    return true;
  }
};

}  // namespace

std::vector<SubMeshLifetime> submesh_lifetimes(const Sequence& seq) {
  std::map<int, double> offsets;  // slice id -> offset
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices) offsets.emplace(s.id, s.offset);
  std::vector<std::pair<double, int>> order;
  for (const auto& [id, off] : offsets) order.push_back({off, id});
  std::sort(order.begin(), order.end());
  std::vector<SubMeshLifetime> out;
  for (std::size_t k = 0; k + 1 < order.size(); ++k) {
    const int lo = order[k].second, hi = order[k + 1].second;
    SubMeshLifetime cur;
    for (std::size_t t = 0; t < seq.frames.size(); ++t) {
      const Slice* a = find_slice(seq.frames[t], lo);
      const Slice* b = find_slice(seq.frames[t], hi);
      const int na = a ? static_cast<int>(a->contours.size()) : 0, nb = b ? static_cast<int>(b->contours.size()) : 0;
      const int ti = static_cast<int>(t);
      if (t > 0 && na == cur.contours_below && nb == cur.contours_above) {
        cur.last_frame = ti;
        continue;
      }
      if (t > 0 && (cur.contours_below > 0 || cur.contours_above > 0)) out.push_back(cur);
      cur = {lo, hi, ti, ti, na, nb};
    }
    if (cur.contours_below > 0 || cur.contours_above > 0) out.push_back(cur);
  }
  return out;
}

MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0, const std::vector<TriangleMesh>& surfaces,
                            const MorphOptions& opt, MorphReport* report) {
  if (opt.method == MorphMethod::RbfProject && surfaces.size() != seq.frames.size())
    throw SolverError(ErrorCode::Internal, {}, "morph_sequence: RbfProject needs one surface per frame");
  return morph_sequence(seq, frame0, [&surfaces](std::size_t t) -> const TriangleMesh& { return surfaces[t]; }, opt,
                        report);
}

MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0,
                            const std::function<const TriangleMesh&(std::size_t)>& surface_of, const MorphOptions& opt,
                            MorphReport* report) {
  const std::size_t frames = seq.frames.size();
  MeshSequence out;
  out.triangles = frame0.triangles;
  out.positions.resize(std::max<std::size_t>(1, frames));
  out.positions[0] = frame0.positions;
  for (const Frame& f : seq.frames) out.times_ms.push_back(f.time_ms);
  MorphReport local;
  MorphReport& rep = report ? *report : local;
  rep.frames.assign(frames, {});
  rep.submeshes = submesh_lifetimes(seq);
  const bool project = opt.method == MorphMethod::RbfProject;

  const std::size_t nv = frame0.positions.size();
  const auto nb = vertex_neighbours(nv, frame0.triangles);
  const std::vector<Chain> chains = find_chains(seq, frame0);
  Bands bands;  // frame 0's, between the chains' slices
  {
    std::map<double, int> by_height;
    for (const Chain& c : chains) by_height[dot(c.plane.origin, seq.normal)] = c.slice;
    for (const auto& [h, id] : by_height) {
      bands.heights.push_back(h);
      bands.slice_ids.push_back(id);
    }
    bands.areas = band_areas(frame0.positions, frame0.triangles, seq.normal, bands.heights);
    bands.perimeters = slice_perimeters(seq.frames.front());
    for (const Slice& s0 : seq.frames.front().slices) bands.counts[s0.id] = s0.contours.size();
  }
  std::vector<std::vector<std::uint32_t>> incident(nv);
  for (std::size_t f = 0; f < frame0.triangles.size(); ++f)
    for (std::uint32_t v : frame0.triangles[f]) incident[v].push_back(static_cast<std::uint32_t>(f));
  // The same adjacency as flat arrays.
  std::vector<std::size_t> ring_start(nv + 1, 0);
  std::vector<std::uint32_t> ring_index;
  for (std::size_t i = 0; i < nv; ++i) {
    ring_index.insert(ring_index.end(), nb[i].begin(), nb[i].end());
    ring_start[i + 1] = ring_index.size();
  }
  // The relaxation works on the vertices in breadth-first order: frame 0's numbering scatters neighbours
  // (left heart: median index gap 4,600 of 22,000 vertices), so every sweep's gathers of the rings missed
  // the cache. Its sweeps are Jacobi sweeps (each writes its own vertex from the last sweep's positions)
  // and each ring keeps its neighbour order, so the order changes no result. Its inner loop reads, per
  // position in that order: the ring (o_ring_*), the rest lengths of its springs (frame 0's edges) and the
  // edges opposite the vertex in its triangles, in the triangles' (outward) order (o_opp_*).
  const std::vector<std::uint32_t> order = breadth_first_order(ring_start, ring_index);  // position → vertex
  std::vector<std::uint32_t> rank(nv);                                                  // vertex → position
  for (std::size_t k = 0; k < nv; ++k) rank[order[k]] = static_cast<std::uint32_t>(k);
  std::vector<std::size_t> o_ring_start(nv + 1, 0), o_opp_start(nv + 1, 0);
  std::vector<std::uint32_t> o_ring_index, o_opp_index;
  std::vector<double> o_ring_rest;
  o_ring_index.reserve(ring_index.size());
  o_ring_rest.reserve(ring_index.size());
  o_opp_index.reserve(6 * frame0.triangles.size());
  for (std::size_t k = 0; k < nv; ++k) {
    const std::uint32_t i = order[k];
    for (std::uint32_t j : nb[i]) {
      o_ring_index.push_back(rank[j]);
      o_ring_rest.push_back(distance(frame0.positions[i], frame0.positions[j]));
    }
    o_ring_start[k + 1] = o_ring_index.size();
    for (std::uint32_t f : incident[i]) {
      const Triangle& tri = frame0.triangles[f];
      const std::size_t c = tri[0] == i ? 0 : tri[1] == i ? 1 : 2;
      o_opp_index.push_back(rank[tri[(c + 1) % 3]]);
      o_opp_index.push_back(rank[tri[(c + 2) % 3]]);
    }
    o_opp_start[k + 1] = o_opp_index.size() / 2;
  }
  // Pinned chain vertices are kept at least this far apart (a fraction of the median edge).
  std::vector<double> edge_lengths;
  for (const Triangle& tri : frame0.triangles)
    edge_lengths.push_back(distance(frame0.positions[tri[0]], frame0.positions[tri[1]]));
  std::nth_element(edge_lengths.begin(), edge_lengths.begin() + static_cast<std::ptrdiff_t>(edge_lengths.size() / 2), edge_lengths.end());
  const double median_edge = edge_lengths.empty() ? 0.0 : edge_lengths[edge_lengths.size() / 2];
  const double pin_spacing = opt.pin_spacing * median_edge;
  const double slide_spacing = project ? opt.slide_spacing * median_edge : 0.0;
  std::map<int, int> counts;
  for (const Slice& s0 : seq.frames.front().slices) counts[s0.id] = static_cast<int>(s0.contours.size());
  SparseMatrix LtL;
  if (project && frames > 1) {
    const SparseMatrix L = uniform_laplacian(nb);
    LtL = SparseMatrix(L.transpose() * L);
  }
  // The system W + αLᵀL depends on the connectivity and on which vertices are pinned to contours:
  // it is factored again only when that set changes (topology events), else reused.
  SparseLdlt solver;
  std::vector<char> factored_for;
  BiharmonicStep biharmonic;  // MorphOptions::biharmonic
  std::vector<std::array<std::uint32_t, 2>> mesh_edges;
  for (std::size_t i = 0; i < nv; ++i)
    for (std::uint32_t j : nb[i])
      if (i < j) mesh_edges.push_back({static_cast<std::uint32_t>(i), j});
  const double pin_weight = 1e8;
  std::vector<Vec3> carry = frame0.positions;
  // Step 5 (the contour fit) of frame t runs as a task beside frame t+1's morph: the next frame starts from
  // the mesh before the fit (carry), so nothing waits for it. Its result depends on its frame only.
  tbb::task_group fits;
  std::vector<std::exception_ptr> fit_errors(frames);
  std::exception_ptr morph_error;
  try {
    for (std::size_t t = 1; t < frames; ++t) {
      std::vector<Vec3> x = carry;  // the previous frame's mesh (before its contour fit)
      if (opt.vertical_deformation) vertical_predeformation(seq, frame0.triangles, static_cast<int>(t), opt, x);
      MorphFrameReport& fr = rep.frames[t];
      std::vector<ChainTarget> matched;
      std::vector<std::vector<Vec3>> lines;  // the matched contours of frame t
      std::set<int> unmatched, held;         // held: slices whose chains do not slide in the relaxation
      match_chains(seq, chains, x, static_cast<int>(t), opt, pin_spacing, slide_spacing, matched, lines, unmatched, fr,
                   rep.events, counts);
      if (project && opt.biharmonic) {
        // Every slice keeps frame t−1's contours: the biharmonic displacement, if the triangles stay good.
        std::vector<Vec3> y;
        if (biharmonic.run(seq, static_cast<int>(t), x, mesh_edges, LtL, opt.threshold, y) &&
            std::all_of(y.begin(), y.end(), [](const Vec3& p) { return is_finite(p); })) {
          const std::vector<Vec3> before_fit = y;
          // The section follows the contours only at the mesh's section points: where a contour has corners
          // between them (coarse, jagged real contours), the same guarded fit as step 5 takes the surface
          // onto it, and the frame is kept only if it gets within fit_goal_mm of every contour sample.
          ContourFitReport cf;
          if (opt.contour_fit) {
            cf = guarded_contour_fit(y, frame0.triangles, contour_fit_samples(frame_contours(seq.frames[t]), opt.fit.step_mm),
                                     std::vector<char>(nv, 0), ring_start, ring_index, opt.retry_min_angle_deg,
                                     opt.fit_min_angle_deg, opt.angle_repair, opt.fit);
          }
          const std::size_t crossings = count_self_intersections(TriangleMesh{y, frame0.triangles});
          const FrameQuality q = frame_quality(y, frame0.triangles, crossings);
          if (acceptable(q, opt) && cf.max_after_mm <= opt.fit_goal_mm) {
            fr.biharmonic = true;
            fr.fit_moved = cf.moved;
            fr.fit_max_before = cf.max_before_mm;
            fr.fit_max_after = cf.max_after_mm;
            carry = before_fit;  // as step 5: the next frame starts from the mesh before the fit
            out.positions[t] = std::move(y);
            continue;
          }
        }
      }
      if (project && slide_spacing > 0) {
        hold_next_to(bands, unmatched, held);
        hold_uneven_bands(bands, surface_of(t), seq.frames[t], seq.normal, opt.slide_anisotropy, held);
      }
      std::vector<std::pair<std::uint32_t, Vec3>> pins;
      for (const ChainTarget& m : matched)
        if (m.pinned) pins.push_back({m.vertex, m.position});

      // 1. The paper's RBF from the matched chain points (subsampled as sources).
      std::vector<Vec3> src, dst;
      const int per_contour = project ? opt.guess_sources_per_contour : opt.sources_per_contour;
      const std::size_t budget = static_cast<std::size_t>(std::max(1, per_contour)) *
                                 static_cast<std::size_t>(std::max(1, fr.matched));
      const std::size_t stride = std::max<std::size_t>(1, matched.size() / budget);
      for (std::size_t k = 0; k < matched.size(); k += stride) {
        src.push_back(x[matched[k].vertex]);
        dst.push_back(matched[k].position);
      }
      add_far_point(x, seq.normal, src, dst);
      fr.sources = static_cast<int>(src.size());
      if (!src.empty()) {
        try {
          deform_rbf(x, src, dst, project ? 1 : opt.rbf_steps);
        } catch (const SolverError&) {
          if (!project) throw;
          x = carry;  // the projection below still fits the frame
        }
      }
      std::vector<char> pinned(nv, 0);
      for (const auto& [v, p] : pins) {
        pinned[v] = 1;
        x[v] = p;
      }
      // Sliding chain vertices: the contour they stay on, and the segment they were last found on.
      std::vector<std::int32_t> slide_line(nv, -1), slide_hint(nv, -1);
      std::vector<char> sliding(nv, 0);  // slides through the relaxation (else only snapped after it, if harmless)
      for (const ChainTarget& m : matched)
        if (m.line >= 0 && !pinned[m.vertex]) {
          slide_line[m.vertex] = m.line;
          sliding[m.vertex] = !held.count(m.slice);
        }
      auto slide = [&](std::size_t i, Vec3 p) {
        return closest_on_loop(lines[static_cast<std::size_t>(slide_line[i])], p, slide_hint[i]);
      };
      std::vector<char> on_contour(nv, 0);
      // Whether moving vertex i to p keeps its ring: no triangle turned by more than 60°, and the ring's
      // smallest angle at least as large as before or as the repair's target.
      // With max_good_loss >= 0, the ring may also lose at most that many angles in 40–80°.
      auto harmless = [&](std::size_t i, Vec3 p, double floor_deg, int max_good_loss = -1) {
        double before = 180, after = 180;
        int good_before = 0, good_after = 0;
        for (std::uint32_t f : incident[i]) {
          const Triangle& tri = frame0.triangles[f];
          Vec3 c[3];
          for (std::size_t k = 0; k < 3; ++k) c[k] = tri[k] == i ? p : x[tri[k]];
          const Vec3 n0 = cross(x[tri[1]] - x[tri[0]], x[tri[2]] - x[tri[0]]), n1 = cross(c[1] - c[0], c[2] - c[0]);
          if (dot(n0, n1) <= 0.5 * norm(n0) * norm(n1)) return false;
          before = std::min(before, min_angle_deg(x[tri[0]], x[tri[1]], x[tri[2]]));
          after = std::min(after, min_angle_deg(c[0], c[1], c[2]));
          if (max_good_loss >= 0) {
            good_before += angles_40_80(x[tri[0]], x[tri[1]], x[tri[2]]);
            good_after += angles_40_80(c[0], c[1], c[2]);
          }
        }
        return after >= std::min(before, floor_deg) && (max_good_loss < 0 || good_after >= good_before - max_good_loss);
      };

      if (project) {
        // 2. Laplacian-regularised projection onto the frame's own surface; pinned vertices held on
        //    their contour points.
        const SurfaceProjector surface(surface_of(t));
        const Projector proj{surface, {}, &order};
        if (pinned != factored_for) {
          SparseMatrix W(static_cast<int>(nv), static_cast<int>(nv));
          std::vector<Eigen::Triplet<double>> w;
          for (std::size_t i = 0; i < nv; ++i) w.emplace_back(static_cast<int>(i), static_cast<int>(i), pinned[i] ? pin_weight : 1.0);
          W.setFromTriplets(w.begin(), w.end());
          if (!factor_lower(solver, SparseMatrix(W + opt.stiffness * LtL)))
            throw SolverError(ErrorCode::Internal, Location{seq.source, -1, static_cast<int>(t)},
                              "failed to factor the deformation system");
          factored_for = pinned;
        }
        const Eigen::MatrixXd ref_term = opt.stiffness * (LtL * to_matrix(x));
        for (int it = 0; it < opt.projection_iterations; ++it) {
          std::vector<Vec3> p = proj.project(x);
          for (std::size_t i = 0; i < nv; ++i)
            if (pinned[i]) p[i] = pin_weight * x[i];
          x = from_matrix(ldlt_solve(solver, Eigen::MatrixXd(to_matrix(p) + ref_term)));
          for (const auto& [v, q] : pins) x[v] = q;
        }
        // The normals of the landing triangles serve the first relaxation round (each round's closing
        // projection gives the next one's), so no pass over the tree is spent on normals alone.
        std::vector<Vec3> normals;
        std::vector<Vec3> p = proj.project(x, &normals);
        double sum = 0, mx = 0;
        for (std::size_t i = 0; i < nv; ++i) {
          if (pinned[i]) continue;
          const double d = distance(p[i], x[i]);
          sum += d;
          mx = std::max(mx, d);
          x[i] = p[i];
        }
        fr.projection_mean = nv ? sum / static_cast<double>(nv) : 0;
        fr.projection_max = mx;
        // 3. Tangential relaxation: many cheap sweeps in the tangent planes, then an exact projection.
        //    Vertices on a contour move along it (they were put there before).
        const double scale = std::sqrt(surface_area(surface_of(t)) / std::max(1e-12, surface_area(frame0)));
        // Curvature weights of the umbrella (MorphOptions::saddle_curvature) in the bands beside slices whose
        // contour count differs from frame 0's (saddles of split or merged contours).
        double curv_dev = opt.saddle_curvature * median_edge;
        std::vector<char> saddle_zone(nv, 0);
        if (curv_dev > 0) {
          const std::vector<std::pair<double, double>> zones = saddle_bands(seq, bands, static_cast<int>(t));
          for (std::size_t i = 0; i < nv; ++i) {
            const double h = dot(x[i], seq.normal);
            for (const auto& [lo, hi] : zones) saddle_zone[i] = saddle_zone[i] || (h >= lo && h <= hi);
          }
        }
        double settled = opt.relax_settled;  // 0 in a retry: its rounds run all their sweeps
        auto relax = [&](int rounds, int sweeps) {
          // Everything the sweeps read, in the breadth-first order (position k is vertex order[k]).
          std::vector<char> held_k(nv), slides_k(nv), zone_k(nv);
          for (std::size_t k = 0; k < nv; ++k) {
            const std::uint32_t i = order[k];
            held_k[k] = pinned[i];
            slides_k[k] = on_contour[i];
            zone_k[k] = curv_dev > 0 && saddle_zone[i];
          }
          std::vector<Vec3> xs(nv), ns(nv), moved(nv), vel(nv);
          // The default blend (springs off, equilateral pull on) steps several vertices at once
          // (sweep_lanes_internal.h; MorphOptions::sweep_lanes), with the same result bit for bit.
          const int lanes = opt.spring_weight == 0 && opt.shape_weight > 0 ? sweep_width(opt.sweep_lanes) : 1;
          detail::SweepArrays arrays;
          arrays.ns = ns.data();
          arrays.ring_start = o_ring_start.data();
          arrays.ring_index = o_ring_index.data();
          arrays.opp_start = o_opp_start.data();
          arrays.opp_index = o_opp_index.data();
          arrays.zone = zone_k.data();
          arrays.curv_dev = curv_dev;
          arrays.shape_weight = opt.shape_weight;
          arrays.beta = opt.relax_momentum;
          arrays.step = opt.relax_step;
          // The free vertices of each block of 512 positions (the same in every round), those with as many
          // neighbours and opposite edges next to each other, so that a group of lanes spends no lane waiting
          // out a longer ring (each vertex's step does not depend on its group or on the order within the block).
          const std::size_t blocks = (nv + 511) / 512;
          std::vector<std::size_t> free_k, block_start(blocks + 1, 0);
          free_k.reserve(nv);
          auto shape_of = [&](std::size_t k) {
            return std::pair(o_ring_start[k + 1] - o_ring_start[k], o_opp_start[k + 1] - o_opp_start[k]);
          };
          for (std::size_t b = 0; b < blocks; ++b) {
            const std::size_t first = free_k.size();
            for (std::size_t k = 512 * b; k < std::min(nv, 512 * (b + 1)); ++k)
              if (!held_k[k] && o_ring_start[k + 1] != o_ring_start[k]) free_k.push_back(k);
            if (lanes > 1)
              std::stable_sort(free_k.begin() + static_cast<std::ptrdiff_t>(first), free_k.end(),
                               [&](std::size_t a, std::size_t c) { return shape_of(a) < shape_of(c); });
            block_start[b + 1] = free_k.size();
          }
          for (int r = 0; r < rounds; ++r) {
            for (std::size_t k = 0; k < nv; ++k) {
              xs[k] = x[order[k]];
              ns[k] = normals[order[k]];
            }
            std::fill(vel.begin(), vel.end(), Vec3{});
            moved = xs;
            const double beta = opt.relax_momentum;
            // A round ends early once the sweeps have settled (MorphOptions::relax_settled; not in a retry).
            const double settled2 = std::pow(std::max(0.0, settled) * median_edge, 2);
            for (int sweep = 0; sweep < sweeps; ++sweep) {
              std::atomic<double> largest{0.0};  // the sweep's largest squared move (a maximum: any order gives it)
              arrays.xs = xs.data();
              tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& range) {
                double biggest = 0.0;
                // One vertex's step: its new velocity and position (before sliding).
                auto single = [&](std::size_t i) {
                  const Vec3 xi = xs[i], n = ns[i];
                  const std::uint32_t* ring = o_ring_index.data() + o_ring_start[i];
                  const std::size_t m = o_ring_start[i + 1] - o_ring_start[i];
                  // Umbrella (uniform Laplacian) move, optionally blended with springs whose rest lengths are
                  // frame 0's edges scaled by the change of area: the springs' equilibrium is a similar copy of
                  // frame 0's triangles (the umbrella keeps any affinely stretched grid), but springs alone can
                  // tangle under strong compression, so the default is the umbrella alone.
                  Vec3 c{}, g{}, mid{}, sp{};
                  const bool weighted = zone_k[i];
                  double wsum = 0;
                  for (std::size_t k = 0; k < m; ++k) {
                    const Vec3 e = xs[ring[k]] - xi;
                    double w = 1.0;
                    // Chord height of the edge over the surface, from the two normals (L²/8R on a sphere).
                    if (weighted)
                      w += (std::abs(dot(e, n)) + std::abs(dot(e, ns[ring[k]]))) / (8.0 * curv_dev);
                    wsum += w;
                    c += w * e;
                    if (opt.spring_weight != 0) {
                      const double len = norm(e);
                      if (len > 0) sp += std::clamp((len - scale * o_ring_rest[o_ring_start[i] + k]) / len, -0.3, 0.3) * e;
                    }
                  }
                  if (opt.shape_weight > 0) {
                    // Equilateral pull: the mean of the apexes of equilateral triangles raised, in the tangent
                    // plane, on the edges (j, k) opposite the vertex: midpoint + √3/2 · n × e · |e| / |n × e|.
                    // Two triangles at a time: one division and one square root instruction for both
                    // (packed_math.h: the same bits as the scalar ones); the sums keep the triangles' order.
                    std::size_t k = o_opp_start[i];
                    const std::size_t k_end = o_opp_start[i + 1];
                    auto edge = [&](std::size_t j, Vec3& e, double& ee, double& s2) {
                      const Vec3 a = xs[o_opp_index[2 * j]] - xi, b = xs[o_opp_index[2 * j + 1]] - xi;
                      e = b - a;
                      mid += a + b;
                      ee = dot(e, e);
                      const double ne = dot(n, e);
                      s2 = ee - ne * ne;
                    };
                    for (; k + 1 < k_end; k += 2) {
                      Vec3 e0, e1;
                      double ee0, s20, ee1, s21;
                      edge(k, e0, ee0, s20);
                      edge(k + 1, e1, ee1, s21);
                      double f[2];
                      sqrt_of_ratios2(ee0, s20, ee1, s21, f);
                      if (s20 > 1e-300) g += f[0] * e0;
                      if (s21 > 1e-300) g += f[1] * e1;
                    }
                    if (k < k_end) {
                      Vec3 e0;
                      double ee0, s20;
                      edge(k, e0, ee0, s20);
                      if (s20 > 1e-300) g += std::sqrt(ee0 / s20) * e0;
                    }
                  }
                  const double inv = 1.0 / static_cast<double>(m);
                  if (weighted) c = (static_cast<double>(m) / wsum) * c;  // the weighted mean, as m × mean (saddle zones)
                  Vec3 d = (opt.spring_weight * sp + (1.0 - opt.spring_weight) * c) * inv;
                  if (opt.shape_weight > 0) {
                    const double no = static_cast<double>(o_opp_start[i + 1] - o_opp_start[i]);
                    const Vec3 pull = (0.5 * mid + 0.8660254037844386 * cross(n, g)) / std::max(1.0, no);
                    d = (1.0 - opt.shape_weight) * d + opt.shape_weight * pull;
                  }
                  d -= dot(d, n) * n;
                  vel[i] = beta * vel[i] + opt.relax_step * d;
                  moved[i] = xi + vel[i];
                };
                auto finish = [&](std::size_t i) {
                  if (slides_k[i]) {
                    moved[i] = slide(order[i], moved[i]);
                    vel[i] = moved[i] - xs[i];
                  }
                  biggest = std::max(biggest, dot(vel[i], vel[i]));
                };
                // Each block's free vertices in groups of `lanes`, the last few two at a time or alone.
                std::size_t group[4];
                int count = 0;
                auto step = [&](int width, const std::size_t* idx) {
                  if (width == 4) detail::sweep_quad(arrays, idx, vel.data(), moved.data());
#if defined(__SSE2__)
                  else if (width == 2) detail::sweep_lanes<detail::Sse2Lanes>(arrays, idx, vel.data(), moved.data());
#endif
                  else single(idx[0]);
                  for (int k = 0; k < width; ++k) finish(idx[k]);
                };
                for (std::size_t b = range.begin(); b != range.end(); ++b) {
                  for (std::size_t f = block_start[b]; f < block_start[b + 1]; ++f) {
                    group[count++] = free_k[f];
                    if (count == lanes) {
                      step(lanes, group);
                      count = 0;
                    }
                  }
                  int done = 0;
                  if (count >= 2 && lanes > 1) {
                    step(2, group);
                    done = 2;
                  }
                  for (; done < count; ++done) step(1, group + done);
                  count = 0;
                }
                double seen = largest.load();
                while (biggest > seen && !largest.compare_exchange_weak(seen, biggest)) {
                }
              });
              std::swap(xs, moved);
              if (settled2 > 0 && largest.load() < settled2) break;
            }
            for (std::size_t k = 0; k < nv; ++k) x[order[k]] = xs[k];
            std::vector<Vec3> q = proj.project(x, &normals);
            for (std::size_t i = 0; i < nv; ++i)
              if (!pinned[i] && !on_contour[i]) x[i] = q[i];
          }
        };
        // A frame that ends with a triangle angle below retry_min_angle_deg, fewer than retry_min_good_share
        // of its angles in 40–80° or crossing triangles (a band crowded as a branch point nears a slice or a
        // contour shrinks fast; sliding chains hold the bands between them to frame 0's vertex count) is
        // done again with no chain vertex put on a contour (only plane snaps that lose no angle in 40–80°)
        // and retry_sweep_factor times the sweeps, retry_attempts times (each with twice the sweeps of the one
        // before) until a try meets the criteria; the best try is kept.
        const std::vector<Vec3> x_start = x, normals_start = normals;
        const std::vector<std::int32_t> hints_start = proj.hints;
        const std::vector<std::int32_t> slide_line_start = slide_line;
        std::vector<Vec3> best;  // the best try so far
        MorphFrameReport best_report;
        FrameQuality best_quality;
        int sweep_factor = 1;
        for (int attempt = 0;; ++attempt) {
          if (attempt >= 1) {
            curv_dev = 0;
            settled = 0;
            sweep_factor = attempt == 1 ? std::max(1, opt.retry_sweep_factor) : 2 * sweep_factor;
            x = x_start;
            normals = normals_start;
            proj.hints = hints_start;
            std::fill(sliding.begin(), sliding.end(), 0);
            std::fill(on_contour.begin(), on_contour.end(), 0);
            std::fill(slide_hint.begin(), slide_hint.end(), -1);
            slide_line = slide_line_start;
            fr.plane_snapped = 0;
            fr.sliding = 0;
            fr.redone = true;
          }
          // Chain vertices of matched contours go onto their contour (the closest point) and slide along
          // it from here on: the mesh then passes through the frame's contours, not only near them.
          for (std::size_t i = 0; i < nv; ++i)
            if (sliding[i]) {
              x[i] = slide(i, x[i]);
              on_contour[i] = 1;
              ++fr.sliding;
            }
          // A retry relaxes sweep_factor times as many rounds, each of relax_sweeps sweeps ended by an exact
          // projection, not rounds sweep_factor times as long: within a round every vertex moves in the
          // tangent plane it had at the round's start, and over 800 sweeps a crowded, strongly bent patch (a
          // basal contour shrinking to a third in one frame) drifts off the surface and folds when projected
          // back.
          relax(opt.relax_iterations * sweep_factor, opt.relax_sweeps);
          // 3b. Chain vertices of matched contours onto their contour (the closest point), where their ring
          //     keeps its smallest angle (or 32°): the mesh then passes through the frame's contours, not only
          //     near them. They slide along it in the repair below. Elsewhere (a contour that shrank, crowding
          //     its chain) they stay where the relaxation put them.
          for (int pass = 0; pass < 2 && attempt == 0; ++pass)
            for (std::size_t i = 0; i < nv; ++i) {
              if (slide_line[i] < 0 || on_contour[i]) continue;
              std::int32_t hint = slide_hint[i];
              const Vec3 q = closest_on_loop(lines[static_cast<std::size_t>(slide_line[i])], x[i], hint);
              if (!harmless(i, q, opt.angle_repair.target_deg)) continue;
              x[i] = q;
              slide_hint[i] = hint;
              on_contour[i] = 1;
              ++fr.sliding;
            }
          // 3b'. Where a chain stayed off its contour (held slices: vertices flowed through the plane), the
          //      mesh vertex nearest the plane on each edge that crosses it goes onto the contour instead, if
          //      harmless: the section then passes through the contour at those vertices, not across a crease.
          auto plane_snap = [&]() {
            const std::vector<std::int32_t> best_line =
                nearest_to_planes(x, ring_start, ring_index, lines, seq.normal, 2.0 * median_edge);
            for (std::size_t i = 0; i < nv; ++i) {
              if (best_line[i] < 0 || on_contour[i] || pinned[i]) continue;
              std::int32_t hint = -1;
              const Vec3 q = closest_on_loop(lines[static_cast<std::size_t>(best_line[i])], x[i], hint);
              if (!harmless(i, q, opt.angle_repair.target_deg, attempt == 0 ? opt.plane_snap_good_loss : 0)) continue;
              x[i] = q;
              slide_line[i] = best_line[i];
              slide_hint[i] = hint;
              on_contour[i] = 1;
              ++fr.plane_snapped;
            }
          };
          if (opt.plane_snap && !lines.empty()) {
            plane_snap();
            // The triangles around the snapped vertices relax again (those slide along their contours), which
            // brings more vertices near the planes for another snap.
            for (int k = 0; k < opt.plane_snap_relax_rounds; ++k) {
              relax(1, opt.relax_sweeps);
              plane_snap();
            }
          }
          // 3c. Where the contour turns by more than corner_angle_deg, the nearest vertex on it moves onto
          //     the corner exactly and stays there (else the edges beside it cut the corner).
          std::vector<char> fixed = pinned;
          {
            std::vector<std::vector<std::uint32_t>> on_line(lines.size());
            for (std::size_t i = 0; i < nv; ++i)
              if (on_contour[i]) on_line[static_cast<std::size_t>(slide_line[i])].push_back(static_cast<std::uint32_t>(i));
            // The nearest vertices up to two edges away, nearest first; the first whose ring keeps 20° (the repair
            // below works around it) moves. A retry puts no chain vertex on its contour, so few lie on it (plane
            // snaps): there any vertex near the corner may take it, the nearest only (biv-me frame 6: a basal
            // contour of 19 points turning by 108°, which the fit alone left 0.08–0.36 mm off as the frames before
            // it changed in their last bits).
            CornerSnapOptions co;
            co.corner_angle_deg = opt.corner_angle_deg;
            co.reach = 2.0 * median_edge;
            co.tries = attempt == 0 ? opt.corner_candidates : 1;
            co.any_vertex = attempt > 0;
            snap_corners(x, lines, on_line, fixed, [&](std::uint32_t v, Vec3 corner) { return harmless(v, corner, 20.0); }, co);
          }
          // 4. The few triangles the relaxation leaves thin (saddles of splitting contours): their vertices
          //    move within the frame's surface (along their contour when on one) to maximise their ring's
          //    smallest angle.
          auto snap_to = [&](std::uint32_t v, Vec3 c) {
            return on_contour[v] ? slide(v, c) : surface.walk(c, nullptr, &proj.hints[v]);
          };
          if (opt.untangle_rounds > 0) fr.intersecting_pairs = untangle(x, frame0.triangles, fixed, snap_to, opt.untangle_rounds);
          if (opt.angle_repair.passes > 0)
            fr.angle_repairs = repair_small_angles(x, frame0.triangles, fixed, snap_to, opt.angle_repair);
          const FrameQuality q = frame_quality(x, frame0.triangles, fr.intersecting_pairs);
          if (attempt == 0 || better(q, best_quality, opt.retry_min_angle_deg)) {
            best = x;
            best_report = fr;
            best_quality = q;
          }
          if (acceptable(q, opt)) break;
          // Tries after the first: retry_attempts, and crossing_retry_attempts more while the best so far
          // still has crossing triangles (the surface would not be valid).
          const int last = std::max(0, opt.retry_attempts) +
                           (best_quality.crossings > 0 ? std::max(0, opt.crossing_retry_attempts) : 0);
          if (attempt >= last) break;
        }
        if (fr.redone) {  // the best of the tries (report: redone, whichever it was)
          x = std::move(best);
          fr = best_report;
          fr.redone = true;
        }
      }
      for (const Vec3& p : x)
        if (!is_finite(p))
          throw SolverError(ErrorCode::Internal, Location{seq.source, -1, static_cast<int>(t)},
                            "the deformation produced non-finite positions");
      carry = x;
      if (!(project && opt.contour_fit)) {
        out.positions[t] = std::move(x);
        continue;
      }
      // 5. The surface onto the frame's contours where it cuts across them (contour_fit.h), as a task (above).
      fits.run([&, t, before = std::move(x), pinned = std::move(pinned)] {
        try {
          std::vector<Vec3> fitted = before;
          const std::vector<Vec3> samples = contour_fit_samples(frame_contours(seq.frames[t]), opt.fit.step_mm);
          ContourFitReport cf = guarded_contour_fit(fitted, frame0.triangles, samples, pinned, ring_start, ring_index,
                                                    opt.retry_min_angle_deg, opt.fit_min_angle_deg, opt.angle_repair, opt.fit);
          if (cf.max_after_mm > opt.fit_goal_mm && opt.fit_fallback_min_angle_deg < opt.fit_min_angle_deg) {
            // Still off its contours by more than the goal: once more from the mesh before the fit, with the
            // lower angle floor; the closer of the two is kept.
            std::vector<Vec3> y = before;
            const ContourFitReport again =
                guarded_contour_fit(y, frame0.triangles, samples, pinned, ring_start, ring_index, opt.retry_min_angle_deg,
                                    opt.fit_fallback_min_angle_deg, opt.angle_repair, opt.fit);
            if (again.max_after_mm < cf.max_after_mm) {
              fitted = std::move(y);
              cf.moved = again.moved;
              cf.max_after_mm = again.max_after_mm;
            }
          }
          MorphFrameReport& r = rep.frames[t];  // only this task writes these fields of frame t
          r.fit_moved = cf.moved;
          r.fit_max_before = cf.max_before_mm;
          r.fit_max_after = cf.max_after_mm;
          out.positions[t] = std::move(fitted);
        } catch (...) {
          fit_errors[t] = std::current_exception();
        }
      });
    }
  } catch (...) {
    morph_error = std::current_exception();
  }
  fits.wait();  // the tasks keep their errors
  // Fits run only for frames before one whose morph failed, so a fit's error is reported first (the lowest
  // frame's), as when the frames were done one after the other.
  for (const std::exception_ptr& e : fit_errors)
    if (e) std::rethrow_exception(e);
  if (morph_error) std::rethrow_exception(morph_error);
  return out;
}

}  // namespace c4d
