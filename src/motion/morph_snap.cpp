// Steps 3b, 3b' and 3c of the 4D morph (Lim et al. 2014, "4D Morphing of the Heart Model"; Miara et al.
// §III.E): mesh vertices onto the frame's matched contours, where their triangles allow it, so that each
// frame passes through its contours and not only near them: the chain vertices of matched contours, the
// vertex nearest each contour's plane on the edges crossing it (where chains were held off their contours),
// and a vertex on every sharp corner of a contour (corner_snap.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "contour4d/metrics/quality.h"
#include "contour4d/motion/corner_snap.h"
#include "contour4d/surface/angle_repair.h"
#include "morph_work_internal.h"

namespace c4d::detail {
namespace {

constexpr double kSnapReachEdges = 2.0;  // plane and corner snaps: candidates within this × the median edge
constexpr double kCornerFloorDeg = 20;   // a corner snap keeps its vertex's ring above this (the repair works
                                         // around it)
constexpr double kCornerAngleDeg = 30;   // a matched contour turning more than this at one of its points gets the
                                         // nearest vertex on it exactly there (as frame 0's resampled contours keep
                                         // such corners)

// Whether moving vertex i to p keeps its ring: no triangle turned by more than 60°, and the ring's
// smallest angle at least as large as before or as floor_deg. With max_good_loss >= 0, the ring may
// also lose at most that many angles in 40–80°.
bool harmless(const MorphWork& w, const FrameWork& f, std::size_t i, Vec3 p, double floor_deg, int max_good_loss = -1) {
  const std::vector<Vec3>& x = f.x;
  double before = 180, after = 180;
  int good_before = 0, good_after = 0;
  for (std::uint32_t t : w.incident[i]) {
    const Triangle& tri = w.frame0.triangles[t];
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
}

// Per contour of `lines`, its segments in runs of kRun with their bounding boxes (within_reach).
constexpr std::size_t kRun = 16;
using SegmentBoxes = std::vector<std::vector<std::array<Vec3, 2>>>;

SegmentBoxes segment_boxes(const std::vector<std::vector<Vec3>>& lines) {
  SegmentBoxes boxes(lines.size());
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
  return boxes;
}

// Whether contour l passes within `reach` of q, as distance(closest_on_loop(...)) <= reach but faster:
// boxes farther than reach (with a margin well above rounding) skipped, and the first segment within
// reach ends it.
bool within_reach(const std::vector<Vec3>& L, const std::vector<std::array<Vec3, 2>>& boxes, Vec3 q, double reach) {
  const double margin = 1e-6 * (1.0 + reach);
  const std::size_t n = L.size();
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    const auto& [lo, hi] = boxes[b];
    const Vec3 d{std::max({lo.x - q.x, 0.0, q.x - hi.x}), std::max({lo.y - q.y, 0.0, q.y - hi.y}),
                 std::max({lo.z - q.z, 0.0, q.z - hi.z})};
    if (norm(d) > reach + margin) continue;
    for (std::size_t k = b * kRun; k < std::min(n, (b + 1) * kRun); ++k)
      if (distance(closest_on_segment(L[k], L[(k + 1) % n], q), q) <= reach) return true;
  }
  return false;
}

// The plane snap's candidates: on every mesh edge (rings in CSR form) that crosses the plane of one of
// `lines` within `reach` of that line, the endpoint nearer the plane. Per vertex: the line of its nearest
// such crossing, -1 for none.
std::vector<std::int32_t> nearest_to_planes(const std::vector<Vec3>& x, const std::vector<std::size_t>& ring_start,
                                            const std::vector<std::uint32_t>& ring_index,
                                            const std::vector<std::vector<Vec3>>& lines, Vec3 normal, double reach) {
  const std::size_t nv = x.size();
  std::vector<double> line_h(lines.size());
  for (std::size_t l = 0; l < lines.size(); ++l) line_h[l] = dot(lines[l].front(), normal);
  const SegmentBoxes boxes = segment_boxes(lines);
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
          if (within_reach(lines[l], boxes[l], c, reach))
            found[b].push_back({static_cast<std::uint32_t>(v), static_cast<std::int32_t>(l), gap});
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

}  // namespace

// Chain vertices that slide (f.sliding) go onto their contour (the closest point) and slide along it from
// here on: the mesh then passes through the frame's contours, not only near them.
void put_sliding_on_contours(FrameWork& f) {
  for (std::size_t i = 0; i < f.x.size(); ++i)
    if (f.sliding[i]) {
      f.x[i] = slide(f, i, f.x[i]);
      f.on_contour[i] = 1;
      ++f.fr.sliding;
    }
}

// Step 3b: after the relaxation, the other chain vertices of matched contours onto their contour (the
// closest point), where their ring keeps its smallest angle (or angle_repair.target_deg); two passes. They
// slide along it in the repair. Elsewhere (a contour that shrank, crowding its chain) they stay where the
// relaxation put them.
void snap_chains_to_contours(const MorphWork& w, FrameWork& f) {
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < w.nv; ++i) {
      if (f.slide_line[i] < 0 || f.on_contour[i]) continue;
      std::int32_t hint = f.slide_hint[i];
      const Vec3 q = closest_on_loop(f.lines[static_cast<std::size_t>(f.slide_line[i])], f.x[i], hint);
      if (!harmless(w, f, i, q, w.opt.angle_repair.target_deg)) continue;
      f.x[i] = q;
      f.slide_hint[i] = hint;
      f.on_contour[i] = 1;
      ++f.fr.sliding;
    }
}

// Step 3b': where a chain stayed off its contour (held slices: vertices flowed through the plane), the mesh
// vertex nearest the plane on each edge that crosses it goes onto the contour instead, if harmless: the
// section then passes through the contour at those vertices, not across a crease.
void snap_to_planes(const MorphWork& w, FrameWork& f, const MorphTry& tr) {
  const std::vector<std::int32_t> best_line =
      nearest_to_planes(f.x, w.ring_start, w.ring_index, f.lines, w.seq.normal, kSnapReachEdges * w.median_edge);
  for (std::size_t i = 0; i < w.nv; ++i) {
    if (best_line[i] < 0 || f.on_contour[i]) continue;
    std::int32_t hint = -1;
    const Vec3 q = closest_on_loop(f.lines[static_cast<std::size_t>(best_line[i])], f.x[i], hint);
    if (!harmless(w, f, i, q, w.opt.angle_repair.target_deg, tr.plane_snap_good_loss)) continue;
    f.x[i] = q;
    f.slide_line[i] = best_line[i];
    f.slide_hint[i] = hint;
    f.on_contour[i] = 1;
    ++f.fr.plane_snapped;
  }
}

// Step 3c: where a matched contour turns by more than kCornerAngleDeg, the nearest vertex on it moves onto
// the corner exactly and stays there (else the edges beside it cut the corner). The nearest vertices up to
// two edges away, nearest first; the first whose ring keeps kCornerFloorDeg moves. A retry puts no chain
// vertex on its contour, so few lie on it (plane snaps): there any vertex near the corner may take it, the
// nearest only (a coarse contour turning sharply, which the fit alone can leave a few tenths of a mm off).
// Returns the vertices that stay.
std::vector<char> snap_contour_corners(const MorphWork& w, FrameWork& f, const MorphTry& tr) {
  std::vector<char> fixed(w.nv, 0);
  std::vector<std::vector<std::uint32_t>> on_line(f.lines.size());
  for (std::size_t i = 0; i < w.nv; ++i)
    if (f.on_contour[i]) on_line[static_cast<std::size_t>(f.slide_line[i])].push_back(static_cast<std::uint32_t>(i));
  CornerSnapOptions co;
  co.corner_angle_deg = kCornerAngleDeg;
  co.reach = kSnapReachEdges * w.median_edge;
  co.tries = tr.corner_candidates;
  co.any_vertex = tr.corner_any_vertex;
  snap_corners(
      f.x, f.lines, on_line, fixed,
      [&](std::uint32_t v, Vec3 corner) { return harmless(w, f, v, corner, kCornerFloorDeg); }, co);
  return fixed;
}

}  // namespace c4d::detail
