// Lim et al. 2014, "Contour Matching" (Fig. 7): intersection points as break points, proportional
// mapping of the segments between them. When the contours do not cross (one inside the other, or
// apart), the paper's rule has no break points; we then map by arc length from the start offset that
// minimises the summed squared motion, which keeps the cyclic order (no crossing paths).
#include "contour4d/motion/contour_matching.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contour4d/core/contour.h"

namespace c4d {
namespace {

// A closed polyline with cumulative arc length, evaluated at any arc position (cyclic).
struct ArcPolygon {
  std::vector<Vec2> p;
  std::vector<double> s;  // s[i] = arc length at p[i]; s[n] = total
  double length = 0;

  explicit ArcPolygon(std::vector<Vec2> pts) : p(std::move(pts)) {
    s.resize(p.size() + 1, 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) s[i + 1] = s[i] + norm(p[(i + 1) % p.size()] - p[i]);
    length = s.back();
  }
  double wrap(double t) const {
    if (t >= 0 && t < length) return t;  // what fmod gives there, without the call
    t = std::fmod(t, length);
    return t < 0 ? t + length : t;
  }
  Vec2 at(double t) const {
    t = wrap(t);
    const auto it = std::upper_bound(s.begin(), s.end(), t);
    return point(static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - s.begin()) - 1)), t);
  }
  // at(t) for increasing t (after wrapping), as when a whole contour is mapped: the segment is found by
  // stepping on from the last one (`cursor`, 0 to start) instead of a binary search; the same segment,
  // so the same point.
  Vec2 at_from(double t, std::size_t& cursor) const {
    t = wrap(t);
    if (cursor >= s.size() || s[cursor] > t) cursor = 0;
    while (cursor + 1 < s.size() && s[cursor + 1] <= t) ++cursor;
    return point(cursor, t);
  }

 private:
  // The point at arc position t (wrapped) on segment i (s[i] <= t).
  Vec2 point(std::size_t i, double t) const {
    if (i >= p.size()) i = p.size() - 1;
    const double len = s[i + 1] - s[i];
    const double f = len > 0 ? (t - s[i]) / len : 0.0;
    return p[i] + f * (p[(i + 1) % p.size()] - p[i]);
  }
};

struct Crossing {
  double s_source;
  double s_target;
};

std::vector<Crossing> crossings(const ArcPolygon& a, const ArcPolygon& b) {
  std::vector<Crossing> out;
  const std::size_t na = a.p.size(), nb = b.p.size();
  for (std::size_t i = 0; i < na; ++i) {
    const Vec2 p = a.p[i], r = a.p[(i + 1) % na] - p;
    for (std::size_t j = 0; j < nb; ++j) {
      const Vec2 q = b.p[j], sv = b.p[(j + 1) % nb] - q;
      const double den = cross(r, sv);
      if (std::abs(den) < 1e-15) continue;  // parallel: touching, not crossing
      const double t = cross(q - p, sv) / den, u = cross(q - p, r) / den;
      // Half-open intervals so a crossing exactly at a vertex is counted once.
      if (t >= 0 && t < 1 && u >= 0 && u < 1)
        out.push_back({a.s[i] + t * (a.s[i + 1] - a.s[i]), b.s[j] + u * (b.s[j + 1] - b.s[j])});
    }
  }
  std::sort(out.begin(), out.end(), [](const Crossing& x, const Crossing& y) { return x.s_source < y.s_source; });
  return out;
}

// True when the crossings, taken in source order, also advance monotonically (cyclically) along the target.
bool same_cyclic_order(const std::vector<Crossing>& c, double target_length) {
  double total = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    double d = c[(i + 1) % c.size()].s_target - c[i].s_target;
    if (d <= 0) d += target_length;
    total += d;
  }
  return std::abs(total - target_length) < 1e-9 * std::max(1.0, target_length);
}

}  // namespace

ContourMatch match_contour(const std::vector<Vec2>& source, const std::vector<Vec2>& target_in) {
  // Same orientation for both, so that arc length advances the same way round.
  std::vector<Vec2> target = target_in;
  if ((signed_area(source) > 0) != (signed_area(target) > 0)) std::reverse(target.begin(), target.end());
  const ArcPolygon a(source), b(target);
  ContourMatch match;
  match.targets.resize(source.size());
  match.arc.resize(source.size());
  match.polygon = target;

  const std::vector<Crossing> cs = crossings(a, b);
  if (cs.size() >= 2 && same_cyclic_order(cs, b.length)) {
    match.method = MatchMethod::BreakPoints;
    match.break_points = static_cast<int>(cs.size());
    const std::size_t k = cs.size();
    for (std::size_t i = 0; i < source.size(); ++i) {
      const double s = a.s[i];
      // Segment [cs[j], cs[j+1]) containing s, cyclically.
      std::size_t j = k - 1;
      for (std::size_t m = 0; m < k; ++m)
        if (cs[m].s_source <= s) j = m;
      const Crossing& c0 = cs[j];
      const Crossing& c1 = cs[(j + 1) % k];
      double span_a = c1.s_source - c0.s_source, off_a = s - c0.s_source;
      if (span_a <= 0) span_a += a.length;
      if (off_a < 0) off_a += a.length;
      double span_b = c1.s_target - c0.s_target;
      if (span_b <= 0) span_b += b.length;
      const double u = c0.s_target + (span_a > 0 ? off_a / span_a : 0.0) * span_b;
      match.arc[i] = b.wrap(u);
      match.targets[i] = b.at(u);
    }
    return match;
  }

  // No usable crossings: arc-length mapping from the best start offset (coarse scan, then refine).
  match.method = MatchMethod::Aligned;
  const double ratio = b.length / a.length;
  auto cost = [&](double offset) {
    double c = 0;
    std::size_t cursor = 0;  // the arc positions increase with i (wrapping once at most)
    for (std::size_t i = 0; i < source.size(); ++i) {
      const Vec2 d = b.at_from(offset + a.s[i] * ratio, cursor) - source[i];
      c += dot(d, d);
    }
    return c;
  };
  const int coarse = 256;
  double best = 0, best_cost = std::numeric_limits<double>::infinity();
  for (int k = 0; k < coarse; ++k) {
    const double off = b.length * k / coarse;
    const double c = cost(off);
    if (c < best_cost) {
      best_cost = c;
      best = off;
    }
  }
  double lo = best - b.length / coarse, hi = best + b.length / coarse;
  for (int it = 0; it < 40; ++it) {  // golden-section search around the coarse minimum
    const double m1 = lo + 0.381966 * (hi - lo), m2 = hi - 0.381966 * (hi - lo);
    if (cost(m1) < cost(m2))
      hi = m2;
    else
      lo = m1;
  }
  best = 0.5 * (lo + hi);
  for (std::size_t i = 0; i < source.size(); ++i) {
    match.arc[i] = b.wrap(best + a.s[i] * ratio);
    match.targets[i] = b.at(best + a.s[i] * ratio);
  }
  return match;
}

Vec2 target_between(const ContourMatch& m, std::size_t i, double f) {
  const std::size_t n = m.arc.size();
  if (n == 0 || m.polygon.size() < 2) return m.targets.empty() ? Vec2{} : m.targets[i % m.targets.size()];
  const ArcPolygon b(m.polygon);
  if (!(b.length > 0)) return m.targets[i % n];
  double span = m.arc[(i + 1) % n] - m.arc[i % n];
  if (span < 0) span += b.length;  // the mapping keeps the cyclic order: the next target is ahead
  return b.at(m.arc[i % n] + std::clamp(f, 0.0, 1.0) * span);
}

}  // namespace c4d
