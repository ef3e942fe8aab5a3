// Closest points by walking over the surface: the projection of Botsch & Kobbelt's isotropic
// remeshing ("A remeshing approach to multiresolution modeling", 2004: "project each vertex back onto
// the original surface"), the refinement step of Lim et al. 2014, "Surface Smoothing and Refinement",
// done from each vertex's last closest triangle instead of a tree query; the one-frame surface's
// small-angle repair snaps its trial positions the same way.
#include "contour4d/metrics/surface_walk.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace c4d {

Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double sum = va + vb + vc;
  if (!(sum > 0)) {  // degenerate triangle: the closest of its edges
    auto on_segment = [&](const Vec3& s, const Vec3& e) {
      const Vec3 se = e - s;
      const double l = dot(se, se);
      const double w = l > 0 ? std::clamp(dot(p - s, se) / l, 0.0, 1.0) : 0.0;
      return s + w * se;
    };
    Vec3 best = on_segment(a, b);
    for (const Vec3& q : {on_segment(b, c), on_segment(c, a)})
      if (dot(p - q, p - q) < dot(p - best, p - best)) best = q;
    return best;
  }
  const double denom = 1.0 / sum;
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

SurfaceWalk make_surface_walk(TriangleMesh surface, std::vector<std::int32_t> patch) {
  SurfaceWalk w;
  w.positions = std::move(surface.positions);
  w.triangles = std::move(surface.triangles);
  w.patch = std::move(patch);
  w.patch.resize(w.triangles.size(), 0);
  w.start.assign(w.positions.size() + 1, 0);
  for (const Triangle& t : w.triangles)
    for (std::uint32_t v : t) ++w.start[v + 1];
  for (std::size_t v = 0; v < w.positions.size(); ++v) w.start[v + 1] += w.start[v];
  w.tris.resize(w.start.back());
  std::vector<std::uint32_t> fill(w.start.begin(), w.start.end() - 1);
  for (std::size_t k = 0; k < w.triangles.size(); ++k)
    for (std::uint32_t v : w.triangles[k]) w.tris[fill[v]++] = static_cast<std::uint32_t>(k);
  w.balls.resize(w.triangles.size());
  w.planes.assign(w.triangles.size(), {0.0, 0.0, 0.0, 0.0, 0.0});
  for (std::size_t k = 0; k < w.triangles.size(); ++k) {
    const Triangle& t = w.triangles[k];
    const Vec3 c = (w.positions[t[0]] + w.positions[t[1]] + w.positions[t[2]]) / 3.0;
    const double r =
        std::max({distance(c, w.positions[t[0]]), distance(c, w.positions[t[1]]), distance(c, w.positions[t[2]])});
    w.balls[k] = {c.x, c.y, c.z, r};
    const Vec3 a = w.positions[t[0]], n = cross(w.positions[t[1]] - a, w.positions[t[2]] - a);
    const double ln = norm(n);
    if (ln > 0 && std::isfinite(ln)) {
      const Vec3 u = n / ln;
      const double offset = dot(u, a);
      double slack = 0.0;
      for (std::uint32_t v : t) slack = std::max(slack, std::abs(dot(u, w.positions[v]) - offset));
      w.planes[k] = {u.x, u.y, u.z, offset, slack};
    }
  }
  return w;
}

namespace {

// A walk step's candidates around triangle t: the triangles of its corners in order, but t itself, those
// of another patch and those around an earlier corner (met there already).
template <class F>
void step_candidates(const SurfaceWalk& walk, std::uint32_t t, F&& f) {
  const Triangle here = walk.triangles[t];
  const std::int32_t pid = walk.patch[t];
  for (int i = 0; i < 3; ++i)
    for (std::uint32_t k = walk.start[here[i]]; k < walk.start[here[i] + 1]; ++k) {
      const std::uint32_t cand = walk.tris[k];
      if (cand == t || walk.patch[cand] != pid) continue;
      // A triangle across an edge is also around an earlier corner: measured there already (a second
      // measure is never strictly nearer, so skipping it changes nothing).
      const Triangle& ct = walk.triangles[cand];
      bool seen = false;
      for (int e = 0; e < i; ++e) seen = seen || ct[0] == here[e] || ct[1] == here[e] || ct[2] == here[e];
      if (!seen) f(cand);
    }
}

}  // namespace

void add_neighbour_lists(SurfaceWalk& walk) {
  const std::size_t nt = walk.triangles.size();
  walk.near_start.assign(nt + 1, 0);
  walk.near.clear();
  walk.near.reserve(13 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    step_candidates(walk, static_cast<std::uint32_t>(t), [&](std::uint32_t c) { walk.near.push_back(c); });
    walk.near_start[t + 1] = static_cast<std::uint32_t>(walk.near.size());
  }
}

std::int32_t walk_start(const SurfaceWalk& walk, std::uint32_t v) {
  if (v + 1 >= walk.start.size() || walk.start[v] == walk.start[v + 1]) return -1;
  return static_cast<std::int32_t>(walk.tris[walk.start[v]]);
}

Vec3 walk_closest(const SurfaceWalk& walk, const Vec3& p, std::int32_t& hint) {
  auto dist2 = [&](std::int32_t k, Vec3* q) {
    const Triangle& tr = walk.triangles[static_cast<std::size_t>(k)];
    *q = closest_on_triangle(p, walk.positions[tr[0]], walk.positions[tr[1]], walk.positions[tr[2]]);
    const Vec3 d = p - *q;
    return dot(d, d);
  };
  Vec3 best_q;
  double best = dist2(hint, &best_q);
  double reach = std::sqrt(best);
  // The plane test's margin: far above the rounding of a closest point, of its distance and of the
  // plane test itself (about 1e-16 of the coordinates), so a triangle it skips is never measured nearer
  // than the best.
  const double margin = 1e-9 * (1.0 + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
  const bool listed = !walk.near_start.empty();
  for (int step = 0; step < 256; ++step) {
    std::int32_t next = hint;
    // A triangle whose ball lies farther than the best distance cannot be nearer (the margin covers the
    // rounding of this test): not measured.
    auto measure = [&](std::uint32_t cand) {
      const auto& ball = walk.balls[cand];
      const double bx = p.x - ball[0], by = p.y - ball[1], bz = p.z - ball[2], lim = ball[3] + reach;
      if (bx * bx + by * by + bz * bz > (1.0 + 1e-9) * lim * lim) return;
      // Nor one whose plane lies farther: the triangle lies within `slack` of its plane, so its distance
      // is at least the plane's less that.
      const auto& pl = walk.planes[cand];
      if (std::abs(pl[0] * p.x + pl[1] * p.y + pl[2] * p.z - pl[3]) > reach + margin + pl[4]) return;
      Vec3 q;
      const double d = dist2(static_cast<std::int32_t>(cand), &q);
      if (d < best) {
        best = d;
        reach = std::sqrt(best);
        best_q = q;
        next = static_cast<std::int32_t>(cand);
      }
    };
    const auto h = static_cast<std::uint32_t>(hint);
    if (listed) {
      for (std::uint32_t k = walk.near_start[h]; k < walk.near_start[h + 1]; ++k) measure(walk.near[k]);
    } else {
      step_candidates(walk, h, measure);
    }
    if (next == hint) break;
    hint = next;
  }
  return best_q;
}

}  // namespace c4d
