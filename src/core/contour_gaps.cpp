// Contours missing from some frames, filled in time (contour_gaps.h). Neither paper has it: Lim et al. and Miara
// et al. take every frame as fully contoured. A frame without a slice's contour would otherwise bridge the slices
// around it (16 mm or more on a cine stack), while the same slice one frame away is a much closer guess.
#include "contour4d/core/contour_gaps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "contour4d/core/contour.h"

namespace c4d {

namespace {

// The frames' contours of one label on one slice id: per frame the count and the first one.
struct SliceHistory {
  double offset = 0;
  std::vector<int> count;
  std::vector<const Contour*> first;
};

std::map<int, SliceHistory> histories(const Sequence& seq, const std::string& label) {
  std::map<int, SliceHistory> out;
  const std::size_t n = seq.frames.size();
  for (std::size_t f = 0; f < n; ++f)
    for (const Slice& s : seq.frames[f].slices)
      for (const Contour& c : s.contours) {
        if (c.label != label) continue;
        SliceHistory& h = out[s.id];
        if (h.count.empty()) h.count.assign(n, 0), h.first.assign(n, nullptr);
        h.offset = s.offset;
        if (h.count[f]++ == 0) h.first[f] = &c;
      }
  return out;
}

// True when frame f holds the label on slices below and above `offset`.
bool inside_structure(const std::map<int, SliceHistory>& h, std::size_t f, double offset) {
  bool below = false, above = false;
  for (const auto& [id, s] : h) {
    if (s.count[f] == 0) continue;
    below = below || s.offset < offset;
    above = above || s.offset > offset;
  }
  return below && above;
}

// `n` points at equal arc length along a closed polygon (plane coordinates), counter-clockwise.
std::vector<Vec2> resample_ccw(std::vector<Vec2> p, std::size_t n) {
  if (signed_area(p) < 0) std::reverse(p.begin(), p.end());
  std::vector<double> at(p.size() + 1, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) at[i + 1] = at[i] + norm(p[(i + 1) % p.size()] - p[i]);
  std::vector<Vec2> out;
  std::size_t seg = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double s = at.back() * static_cast<double>(k) / static_cast<double>(n);
    while (seg + 1 < p.size() && at[seg + 1] <= s) ++seg;
    const double len = at[seg + 1] - at[seg];
    const double t = len > 0 ? (s - at[seg]) / len : 0.0;
    out.push_back(p[seg] + t * (p[(seg + 1) % p.size()] - p[seg]));
  }
  return out;
}

// b turned (cyclically) to match a point by point best.
std::vector<Vec2> best_start(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  const std::size_t n = a.size();
  std::size_t shift = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    double d = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 e = a[i] - b[(i + k) % n];
      d += dot(e, e);
    }
    if (d < best) best = d, shift = k;
  }
  std::vector<Vec2> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = b[(i + shift) % n];
  return out;
}

std::vector<Vec2> in_plane(const Sequence& seq, const Contour& c) {
  std::vector<Vec2> out;
  for (const Vec3& p : c.points) out.push_back({dot(p, seq.u), dot(p, seq.v)});
  return out;
}

// The contour at weight w between a and b (same slice, same label).
Contour blend(const Sequence& seq, const Contour& a, const Contour& b, double w) {
  const std::size_t n = std::max(a.points.size(), b.points.size());
  const std::vector<Vec2> pa = resample_ccw(in_plane(seq, a), n);
  const std::vector<Vec2> pb = best_start(pa, resample_ccw(in_plane(seq, b), n));
  double h = 0;  // the plane's height along the normal
  for (const Vec3& p : a.points) h += dot(p, seq.normal);
  h /= static_cast<double>(a.points.size());
  Contour out{a.label, a.slice, {}};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 q = (1 - w) * pa[i] + w * pb[i];
    out.points.push_back(seq.u * q.x + seq.v * q.y + seq.normal * h);
  }
  return out;
}

// The nearest frame from f (stepping by `step`, cyclically) whose slice holds exactly one contour; -1 if none.
int nearest_with_one(const SliceHistory& h, int f, int step, int& distance) {
  const int n = static_cast<int>(h.count.size());
  for (distance = 1; distance < n; ++distance) {
    const int g = ((f + step * distance) % n + n) % n;
    if (h.count[static_cast<std::size_t>(g)] == 1) return g;
  }
  return -1;
}

void add_contour(Frame& frame, int id, double offset, Contour c) {
  for (Slice& s : frame.slices)
    if (s.id == id) {
      s.contours.push_back(std::move(c));
      return;
    }
  const auto at =
      std::find_if(frame.slices.begin(), frame.slices.end(), [&](const Slice& s) { return s.offset > offset; });
  frame.slices.insert(at, Slice{id, offset, {std::move(c)}});
}

// The widest span of frames a fill may bridge: a third of the cycle (at least 2 frames).
int max_span(std::size_t frames) { return std::max(2, static_cast<int>(frames) / 3); }

// The fills of one label, found on the unchanged sequence and then added.
std::vector<std::pair<ContourFill, Contour>> fills_of(const Sequence& seq, const std::string& label) {
  std::vector<std::pair<ContourFill, Contour>> out;
  const std::map<int, SliceHistory> h = histories(seq, label);
  for (const auto& [id, s] : h)
    for (std::size_t f = 0; f < s.count.size(); ++f) {
      if (s.count[f] != 0 || !inside_structure(h, f, s.offset)) continue;
      int back = 0, ahead = 0;
      const int from = nearest_with_one(s, static_cast<int>(f), -1, back);
      const int to = nearest_with_one(s, static_cast<int>(f), +1, ahead);
      // Two distinct frames, not far apart: a copy of the only other frame (a two-phase study's ED for its ES)
      // would be a guess, not an interpolation.
      if (from < 0 || to < 0 || from == to || back + ahead > max_span(s.count.size())) continue;
      const double w = static_cast<double>(back) / (back + ahead);
      Contour c = blend(seq, *s.first[static_cast<std::size_t>(from)], *s.first[static_cast<std::size_t>(to)], w);
      if (is_self_intersecting(in_plane(seq, c))) continue;
      out.push_back({ContourFill{static_cast<int>(f), id, label, from, to, w}, std::move(c)});
    }
  return out;
}

}  // namespace

std::vector<ContourFill> fill_contour_gaps(Sequence& seq) {
  std::vector<ContourFill> done;
  if (seq.frames.size() < 2) return done;
  for (const std::string& label : labels(seq)) {
    auto fills = fills_of(seq, label);
    for (auto& [fill, contour] : fills) {
      const double offset = [&] {
        for (const Frame& fr : seq.frames)
          for (const Slice& s : fr.slices)
            if (s.id == fill.slice) return s.offset;
        return 0.0;
      }();
      add_contour(seq.frames[static_cast<std::size_t>(fill.frame)], fill.slice, offset, std::move(contour));
      done.push_back(fill);
    }
  }
  return done;
}

}  // namespace c4d
