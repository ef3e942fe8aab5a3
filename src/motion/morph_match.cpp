// The 4D morph's frame-to-frame correspondence: Lim et al. 2014, "Contour Matching" (Fig. 7: frame 0's
// contour chains, at the previous frame's positions, matched one-to-one to the frame's contours by the
// similarity index) and "2D contour topological changes" (the sine vertical pre-deformation); Miara et
// al. §III.E (topology events and sub-mesh lifetimes, Fig. 14). Also which chains the relaxation holds in
// their planes, and the saddle bands it weights (morph_work_internal.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "contour4d/connect/similarity.h"
#include "contour4d/motion/contour_matching.h"
#include "contour4d/motion/section.h"
#include "contour4d/motion/vertical_deformation.h"
#include "morph_work_internal.h"

namespace c4d {
namespace detail {

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

namespace {

std::string event_kind(int before, int after) {
  if (before == 0) return "appear";
  if (after == 0) return "vanish";
  if (before == 1 && after > 1) return "split";
  if (before > 1 && after == 1) return "merge";
  return "change";
}

// Chain vertices at least `spacing` apart along a contour of `length` carrying `count` of them: every
// stride-th one (0: none).
std::size_t spacing_stride(double spacing, double length, std::size_t count) {
  const double per = length / static_cast<double>(std::max<std::size_t>(1, count));
  const double ratio = per > 0 ? spacing / per : 1.0;
  return (spacing <= 0 || ratio > 1e6) ? 0
                                       : std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(ratio - 1e-9)));
}

bool on_stride(std::size_t k, std::size_t stride, std::size_t count) {
  return stride > 0 && k % stride == 0 && (stride == 1 || k + stride / 2 < count);
}

// Slices whose contour count changed since the frame before (MorphWork::counts) are reported as events and
// go to f.unmatched, as do those whose count changes into the next frame.
void record_count_changes(MorphWork& w, FrameWork& f) {
  std::map<int, int>& previous_counts = w.counts;
  std::map<int, int> counts;
  for (const Slice& s : w.seq.frames[static_cast<std::size_t>(f.t)].slices)
    counts[s.id] = static_cast<int>(s.contours.size());
  for (const auto& [id, n] : counts)
    if (previous_counts[id] != n) {
      w.rep.events.push_back({f.t, id, event_kind(previous_counts[id], n), previous_counts[id], n});
      f.unmatched.insert(id);
    }
  for (const auto& [id, n] : previous_counts)
    if (n > 0 && !counts.count(id)) w.rep.events.push_back({f.t, id, "vanish", n, 0});
  if (static_cast<std::size_t>(f.t) + 1 < w.seq.frames.size()) {
    std::map<int, int> next;
    for (const Slice& s : w.seq.frames[static_cast<std::size_t>(f.t) + 1].slices)
      next[s.id] = static_cast<int>(s.contours.size());
    for (const auto& [id, n] : counts)
      if (next[id] != n) f.unmatched.insert(id);
  }
  previous_counts = counts;
}

// The chains `idx` of one slice (at f.x) against the slice's contours `ts` in frame t: each chain with a
// one-to-one partner gets its vertices' targets on it (Fig. 7) and the contour as a line; else the slice is
// unmatched.
void match_slice(const MorphWork& w, FrameWork& f, int id, const std::vector<std::size_t>& idx, const Slice& ts) {
  const Plane& pl = w.chains[idx.front()].plane;
  std::vector<std::vector<Vec2>> a, b;
  for (std::size_t c : idx) {
    std::vector<Vec3> pts;
    for (std::uint32_t v : w.chains[c].loop) pts.push_back(f.x[v]);
    a.push_back(flatten(pl, pts));
  }
  for (const Contour& c : ts.contours) b.push_back(flatten(pl, c.points));
  std::vector<std::vector<double>> sim(a.size(), std::vector<double>(b.size()));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) sim[i][j] = contour_similarity(a[i], b[j]);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const int partner = one_to_one_partner(sim, i, w.opt.threshold);
    if (partner < 0) {
      f.unmatched.insert(id);
      continue;
    }
    const ContourMatch m = match_contour(a[i], b[static_cast<std::size_t>(partner)]);
    const Chain& ch = w.chains[idx[i]];
    // Every chain vertex gets a target (they all guide the RBF). A contour that shrank would crowd its
    // chain if all slid along it: only chain vertices slide_spacing apart slide.
    double len = 0;
    for (std::size_t k = 0; k < m.targets.size(); ++k)
      len += norm(m.targets[(k + 1) % m.targets.size()] - m.targets[k]);
    const std::size_t slide = spacing_stride(w.slide_spacing, len, ch.loop.size());
    const int line = static_cast<int>(f.lines.size());
    f.lines.push_back(ts.contours[static_cast<std::size_t>(partner)].points);
    for (std::size_t k = 0; k < ch.loop.size(); ++k)
      f.matched.push_back(
          {ch.loop[k], from_plane(pl, m.targets[k]), on_stride(k, slide, ch.loop.size()) ? line : -1, id});
    ++f.fr.matched;
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

// Chains beside a band whose height scaled more than this × its width since frame 0 (or its width more
// than this × its height) do not slide (hold_uneven_bands).
constexpr double kSlideAnisotropy = 1.1;

// A chain sliding in its plane fixes how many vertices the bands beside it hold. Where a band changed
// shape unevenly since frame 0 (its height, from its area on the frame's own surface over its width,
// scaled more than kSlideAnisotropy × its width, the contours' perimeter ratio, or the reverse), those
// vertices must move through the plane to keep their triangles: the chains bounding it are held.
void hold_uneven_bands(const Bands& b0, const TriangleMesh& surface, const Frame& frame, Vec3 normal,
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
      uneven = height > kSlideAnisotropy * width || width > kSlideAnisotropy * height;
    }
    if (!uneven) continue;
    if (b > 0) held.insert(b0.slice_ids[b - 1]);
    if (b < n) held.insert(b0.slice_ids[b]);
  }
}

// MorphSteps::saddle_curvature: the height ranges (along the stack normal) of the bands beside each slice
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

}  // namespace

// Frame 0's bands between the slices that carry the chains (MorphWork::bands).
void build_bands(MorphWork& w) {
  std::map<double, int> by_height;
  for (const Chain& c : w.chains) by_height[dot(c.plane.origin, w.seq.normal)] = c.slice;
  for (const auto& [h, id] : by_height) {
    w.bands.heights.push_back(h);
    w.bands.slice_ids.push_back(id);
  }
  w.bands.areas = band_areas(w.frame0.positions, w.frame0.triangles, w.seq.normal, w.bands.heights);
  w.bands.perimeters = slice_perimeters(w.seq.frames.front());
  for (const Slice& s0 : w.seq.frames.front().slices) w.bands.counts[s0.id] = s0.contours.size();
}

// Matches the chains (at their current positions f.x) to the contours of frame t, one-to-one per slice;
// fills f.matched for every vertex of a matched chain and f.lines with the matched contours. Reports
// slices whose contour count changed; f.unmatched gets them, those changing into the next frame, and
// those with a chain left without partner.
void match_chains(MorphWork& w, FrameWork& f) {
  std::map<int, std::vector<std::size_t>> by_slice;
  for (std::size_t c = 0; c < w.chains.size(); ++c) by_slice[w.chains[c].slice].push_back(c);
  record_count_changes(w, f);
  const Frame& target = w.seq.frames[static_cast<std::size_t>(f.t)];
  for (const auto& [id, idx] : by_slice) {
    const Slice* ts = find_slice(target, id);
    if (!ts) {
      f.unmatched.insert(id);
      continue;
    }
    match_slice(w, f, id, idx, *ts);
  }
}

// The slices whose chains stay off their contours through the relaxation (f.held): those next to an
// unmatched slice and those bounding a band that changed shape unevenly on frame t's own `surface`.
void hold_chains(const MorphWork& w, FrameWork& f, const TriangleMesh& surface) {
  hold_next_to(w.bands, f.unmatched, f.held);
  hold_uneven_bands(w.bands, surface, w.seq.frames[static_cast<std::size_t>(f.t)], w.seq.normal, f.held);
}

// f.saddle_zone: the vertices in saddle_bands, at f.x (none when MorphSteps::saddle_curvature is 0).
void mark_saddle_zone(const MorphWork& w, FrameWork& f) {
  f.curv_dev = w.steps.saddle_curvature * w.median_edge;
  f.saddle_zone.assign(w.nv, 0);
  if (!(f.curv_dev > 0)) return;
  const std::vector<std::pair<double, double>> zones = saddle_bands(w.seq, w.bands, f.t);
  for (std::size_t i = 0; i < w.nv; ++i) {
    const double h = dot(f.x[i], w.seq.normal);
    for (const auto& [lo, hi] : zones) f.saddle_zone[i] = f.saddle_zone[i] || (h >= lo && h <= hi);
  }
}

// Lim et al. 2014, "2D contour topological changes": where a slice's contours split or merge between
// frames t−1 and t, the mesh (at frame t−1) is first moved along the stack normal by the sine field
// centred on the ridge, so that its section at the incident slice has frame t's contour count and
// the matching finds one-to-one partners there.
void vertical_predeformation(const MorphWork& w, FrameWork& f) {
  const Sequence& seq = w.seq;
  const int t = f.t;
  for (const VerticalMotion& m : vertical_motions(seq, t - 1, t, w.opt.vertical)) {
    if (m.direction == VerticalDirection::None) continue;
    const Frame& before = seq.frames[static_cast<std::size_t>(t - 1)];
    const Slice* incident = find_slice(before, m.incident_slice);
    const Slice* complement = find_slice(before, m.complement_slice);
    if (!incident || !complement) continue;
    const TriangleMesh current{f.x, w.frame0.triangles};
    const auto inc = plane_section(current, slice_plane(seq, *incident));
    const auto comp = plane_section(current, slice_plane(seq, *complement));
    const auto& lone = inc.size() == 1 ? inc : comp;
    const auto& pair = inc.size() == 1 ? comp : inc;
    if (lone.size() != 1 || pair.size() != 2) continue;  // not the 1↔2 case the paper describes
    const Ridge ridge = detect_ridge(current, lone[0], pair[0], pair[1], seq.normal, w.opt.vertical);
    if (!ridge.found) continue;
    std::vector<Vec3> incident_points;
    for (const auto& loop : inc) incident_points.insert(incident_points.end(), loop.begin(), loop.end());
    apply_vertical_deformation(f.x, make_vertical_field(seq, m, ridge.points, incident_points, w.opt.vertical));
  }
}

}  // namespace detail

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
      const Slice* a = detail::find_slice(seq.frames[t], lo);
      const Slice* b = detail::find_slice(seq.frames[t], hi);
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

}  // namespace c4d
