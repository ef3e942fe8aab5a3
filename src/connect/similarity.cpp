// Similarity index of two contours: Lim et al. 2014 (PLOS ONE 9(4): e93747), section
// "Tree-Based Connectivity", eqs. 5 and 6. The perimeter share is measured exactly: every edge of
// one polygon is cut at its crossings with the other, and each piece is classified by its midpoint.
#include "contour4d/connect/similarity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace c4d {
namespace {

struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

Box bounds(const std::vector<Vec2>& p) {
  Box b{p[0].x, p[0].y, p[0].x, p[0].y};
  for (const Vec2& q : p) {
    b.x0 = std::min(b.x0, q.x);
    b.y0 = std::min(b.y0, q.y);
    b.x1 = std::max(b.x1, q.x);
    b.y1 = std::max(b.y1, q.y);
  }
  return b;
}

bool disjoint(const Box& a, const Box& b) { return a.x1 < b.x0 || b.x1 < a.x0 || a.y1 < b.y0 || b.y1 < a.y0; }

// Parameter t in (0,1) along p->q where it crosses segment a->b, if any.
bool crossing(Vec2 p, Vec2 q, Vec2 a, Vec2 b, double& t) {
  const Vec2 r = q - p, s = b - a;
  const double den = cross(r, s);
  if (den == 0.0) return false;  // parallel: collinear overlaps are handled by the midpoint test
  const Vec2 d = a - p;
  t = cross(d, s) / den;
  const double w = cross(d, r) / den;
  return t > 0.0 && t < 1.0 && w >= 0.0 && w <= 1.0;
}

// Whether the edge from b to a crosses the ray from p towards +x (the even-odd rule's step).
bool crosses_ray(Vec2 p, Vec2 a, Vec2 b) {
  if ((a.y > p.y) == (b.y > p.y)) return false;
  return p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
}

}  // namespace

bool point_in_polygon(Vec2 p, const std::vector<Vec2>& poly) {
  bool inside = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++)
    if (crosses_ray(p, poly[i], poly[j])) inside = !inside;
  return inside;
}

namespace {

// The edges of a closed polygon (edge j joins p[j] and p[j + 1]) in horizontal bands of equal height
// over its y range: each edge is listed in every band its y range touches, so every edge that can
// meet a y range (a crossing, a ray at height y, a point within tol) is among the bands' edges. The
// exact tests then run on those edges only, with the same arithmetic as a test of every edge.
struct EdgeBands {
  double y0 = 0, inv = 0;
  std::size_t bands = 1;
  std::vector<std::uint32_t> start, items;
  std::vector<std::uint32_t> stamp;  // last query that listed an edge (lists each edge once per query)
  std::uint32_t query = 0;

  EdgeBands(const std::vector<Vec2>& p, const Box& box) {
    const std::size_t m = p.size();
    bands = std::max<std::size_t>(1, m / 4);
    y0 = box.y0;
    const double h = box.y1 - box.y0;
    inv = h > 0 ? static_cast<double>(bands) / h : 0.0;
    start.assign(bands + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::uint32_t> fill;
      if (pass == 1) {
        for (std::size_t k = 0; k < bands; ++k) start[k + 1] += start[k];
        items.resize(start[bands]);
        fill.assign(start.begin(), start.end() - 1);
      }
      for (std::size_t j = 0; j < m; ++j) {
        const double lo = std::min(p[j].y, p[(j + 1) % m].y), hi = std::max(p[j].y, p[(j + 1) % m].y);
        for (std::size_t k = band(lo), e = band(hi); k <= e; ++k) {
          if (pass == 0)
            ++start[k + 1];
          else
            items[fill[k]++] = static_cast<std::uint32_t>(j);
        }
      }
    }
    stamp.assign(m, 0);
  }
  std::size_t band(double y) const {
    const double f = (y - y0) * inv;
    if (!(f > 0)) return 0;
    return std::min(bands - 1, static_cast<std::size_t>(f));
  }
  // Calls f(j) once for every edge listed in the bands that [lo, hi] touches.
  template <class F>
  void for_edges(double lo, double hi, F&& f) {
    ++query;
    for (std::size_t k = band(lo), e = band(hi); k <= e; ++k)
      for (std::uint32_t i = start[k]; i < start[k + 1]; ++i) {
        const std::uint32_t j = items[i];
        if (stamp[j] == query) continue;
        stamp[j] = query;
        f(j);
      }
  }
};

}  // namespace

double perimeter_inside(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  if (a.size() < 2 || b.size() < 3) return 0.0;
  const Box bb = bounds(b);
  double total = 0.0, inside = 0.0;
  std::vector<double> ts;
  const std::size_t n = a.size(), m = b.size();
  EdgeBands eb_index(b, bb);
  // Band queries are widened by a margin far above rounding: an edge outside them cannot meet the range.
  const double margin = 1e-6 * (bb.x1 - bb.x0 + bb.y1 - bb.y0) + 1e-12;
  const double tol = 1e-9 * (bb.x1 - bb.x0 + bb.y1 - bb.y0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = a[i], q = a[(i + 1) % n];
    const double len = norm(q - p);
    total += len;
    if (len == 0.0) continue;
    const Box eb{std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)};
    if (disjoint(eb, bb)) continue;
    ts.assign({0.0, 1.0});
    eb_index.for_edges(eb.y0 - margin, eb.y1 + margin, [&](std::uint32_t j) {
      double t = 0.0;
      if (crossing(p, q, b[j], b[(j + 1) % m], t)) ts.push_back(t);
    });
    std::sort(ts.begin(), ts.end());
    for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
      const double piece = (ts[k + 1] - ts[k]) * len;
      if (piece <= 0.0) continue;
      const Vec2 mid = p + (0.5 * (ts[k] + ts[k + 1])) * (q - p);
      // point_in_polygon(mid, b) over the edges whose y range holds mid.y (the others cannot toggle it).
      bool in = false;
      if (mid.y >= bb.y0 && mid.y < bb.y1)
        eb_index.for_edges(mid.y, mid.y, [&](std::uint32_t j) {
          if (crosses_ray(mid, b[(j + 1) % m], b[j])) in = !in;
        });
      if (!in) {
        // Pieces lying on b's boundary count as inside (identical contours score 1).
        eb_index.for_edges(mid.y - tol - margin, mid.y + tol + margin, [&](std::uint32_t j) {
          if (!in) in = segment_distance(mid, b[j], b[(j + 1) % m]) <= tol;
        });
      }
      if (in) inside += piece;
    }
  }
  return total > 0.0 ? std::min(1.0, inside / total) : 0.0;
}

double contour_similarity(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  if (a.size() < 3 || b.size() < 3) return 0.0;
  if (disjoint(bounds(a), bounds(b))) return 0.0;
  return std::max(perimeter_inside(a, b), perimeter_inside(b, a));
}

double slice_similarity(const std::vector<std::vector<Vec2>>& a, const std::vector<std::vector<Vec2>>& b) {
  double sum = 0.0;
  for (const auto& ca : a) {
    double best = 0.0;
    for (const auto& cb : b) best = std::max(best, contour_similarity(ca, cb));
    sum += best;
  }
  return sum;
}

}  // namespace c4d
