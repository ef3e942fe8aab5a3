#include "contour4d/core/contour.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace c4d {

double signed_area(const std::vector<Vec2>& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return 0.0;
  // Shoelace formula about the first vertex limits cancellation for polygons far from the origin.
  double a = 0.0;
  const Vec2 o = polygon[0];
  for (std::size_t i = 1; i + 1 < n; ++i) a += cross(polygon[i] - o, polygon[i + 1] - o);
  return 0.5 * a;
}

double perimeter(const std::vector<Vec3>& polygon) {
  double len = 0.0;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) len += distance(polygon[i], polygon[(i + 1) % n]);
  return len;
}

std::vector<Vec3> sample_closed_polyline(const std::vector<Vec3>& polygon, double step) {
  std::vector<Vec3> out;
  const std::size_t n = polygon.size();
  if (n == 0 || !(step > 0.0)) return out;
  double next = 0.0;   // arc length of the next sample
  double start = 0.0;  // arc length at the start of the current edge
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = polygon[i], b = polygon[(i + 1) % n];
    const double len = distance(a, b);
    for (; next < start + len; next += step) out.push_back(a + ((next - start) / len) * (b - a));
    start += len;
  }
  return out;
}

namespace {
int orient(Vec2 a, Vec2 b, Vec2 c) {
  const double v = cross(b - a, c - a);
  return (v > 0) - (v < 0);
}
bool on_segment(Vec2 a, Vec2 b, Vec2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}
bool segments_touch(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) {
    if (o1 != 0 || o2 != 0) return true;
  }
  if (o1 == 0 && on_segment(a, b, c)) return true;
  if (o2 == 0 && on_segment(a, b, d)) return true;
  if (o3 == 0 && on_segment(c, d, a)) return true;
  if (o4 == 0 && on_segment(c, d, b)) return true;
  return false;
}
}  // namespace

bool is_self_intersecting(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  if (n < 4) return false;
  struct Box {
    double x0, x1, y0, y1;
  };
  std::vector<Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = p[i], b = p[(i + 1) % n];
    boxes[i] = {std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y)};
  }
  // Sort edges by their box's x-start so the inner loop stops early (sweep along x).
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return boxes[a].x0 < boxes[b].x0; });
  for (std::size_t oi = 0; oi < n; ++oi) {
    const std::size_t i = order[oi];
    for (std::size_t oj = oi + 1; oj < n; ++oj) {
      const std::size_t j = order[oj];
      if (boxes[j].x0 > boxes[i].x1) break;
      if (boxes[j].y0 > boxes[i].y1 || boxes[j].y1 < boxes[i].y0) continue;
      const bool adjacent = (j == (i + 1) % n) || (i == (j + 1) % n);
      if (adjacent) {
        // Adjacent edges share one vertex; they intersect elsewhere only when they fold back.
        const std::size_t first = (j == (i + 1) % n) ? i : j;
        const Vec2 a = p[first], s = p[(first + 1) % n], b = p[(first + 2) % n];
        if (orient(a, s, b) == 0 && dot(a - s, b - s) > 0) return true;
        continue;
      }
      if (segments_touch(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return true;
    }
  }
  return false;
}

Vec2 closest_on_polyline(Vec2 p, const std::vector<Vec2>& poly, bool closed) {
  const std::size_t n = poly.size();
  const std::size_t edges = n < 2 ? n : (closed ? n : n - 1);
  double best = std::numeric_limits<double>::infinity();
  Vec2 at = p;
  for (std::size_t k = 0; k < edges; ++k) {
    const Vec2 q = closest_on_segment(poly[k], poly[(k + 1) % n], p);
    if (const double d = norm(p - q); d < best) {
      best = d;
      at = q;
    }
  }
  return at;
}

double polyline_distance(Vec2 p, const std::vector<Vec2>& poly, bool closed) {
  if (poly.empty()) return std::numeric_limits<double>::infinity();
  return norm(p - closest_on_polyline(p, poly, closed));
}

}  // namespace c4d
