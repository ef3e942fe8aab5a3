// Contour resampling and canonical form, the preparation step of Lim et al. 2014 ("Reconstruction
// from Segmented Contour Lines" tiles discretised contours). Canonical start and orientation make
// the surface independent of how the input lists a contour; equal-length pieces between kept
// vertices make the point set independent of the direction in which a contour runs.
#include "contour4d/surface/resample.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contour4d/core/contour.h"

namespace c4d {
namespace {

Vec2 area_centroid(const std::vector<Vec2>& p) {
  double a = 0.0;
  Vec2 c{};
  const std::size_t n = p.size();
  const Vec2 o = p[0];  // local origin keeps the sums well conditioned
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 u = p[i] - o, w = p[(i + 1) % n] - o;
    const double cr = cross(u, w);
    a += cr;
    c = c + cr * (u + w);
  }
  if (a == 0.0) {
    Vec2 m{};
    for (const Vec2& q : p) m = m + q;
    return (1.0 / static_cast<double>(n)) * m;
  }
  return o + (1.0 / (3.0 * a)) * c;
}

std::vector<Vec2> dedupe(const std::vector<Vec2>& in) {
  std::vector<Vec2> out;
  for (const Vec2& p : in)
    if (out.empty() || !(out.back() == p)) out.push_back(p);
  while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

// Point at arc length s (any real, wrapped) along the closed polyline with cumulative lengths cum.
Vec2 point_at(const std::vector<Vec2>& p, const std::vector<double>& cum, double s) {
  const double total = cum.back();
  s = std::fmod(s, total);
  if (s < 0) s += total;
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), s) - cum.begin()) - 1;
  const std::size_t n = p.size();
  const std::size_t k = std::min(i, n - 1);
  const double len = cum[k + 1] - cum[k];
  const double t = len > 0 ? (s - cum[k]) / len : 0.0;
  return p[k] + t * (p[(k + 1) % n] - p[k]);
}

// Removes needles: vertices where the contour turns back on itself (more than about 170°), as
// hand-traced and pixel contours sometimes do (out one pixel and back along the same line). No
// surface can pass through such a spike without flat triangles, and it encloses no area.
std::vector<Vec2> without_spikes(std::vector<Vec2> p) {
  for (bool changed = true; changed && p.size() > 3;) {
    changed = false;
    std::vector<Vec2> q;
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 u = p[i] - p[(i + n - 1) % n], w = p[(i + 1) % n] - p[i];
      const double nu = norm(u), nw = norm(w);
      if (nu > 0 && nw > 0 && dot(u, w) < -0.985 * nu * nw && n - (i - q.size()) > 3) {
        changed = true;
        continue;
      }
      q.push_back(p[i]);
    }
    p = dedupe(q);
  }
  return p;
}

}  // namespace

int canonical_start(const std::vector<Vec2>& polygon) {
  const std::size_t n = polygon.size();
  if (n == 0) return 0;
  const Vec2 c = area_centroid(polygon);
  std::vector<double> d(n);
  double dmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) dmax = std::max(dmax, d[i] = norm(polygon[i] - c));
  const double tol = 1e-7 * std::max(dmax, 1e-300);
  int best = -1;
  double best_key = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (d[i] < dmax - tol) continue;
    // Near-ties (symmetric shapes): prefer the vertex whose neighbours are farther out.
    const double key = d[(i + 1) % n] + d[(i + n - 1) % n];
    if (best < 0 || key > best_key + tol) {
      best = static_cast<int>(i);
      best_key = key;
    }
  }
  return best;
}

std::vector<Vec2> canonical_polygon(const std::vector<Vec2>& polygon, bool ccw) {
  std::vector<Vec2> p = dedupe(polygon);
  if (p.size() < 3) return p;
  if ((signed_area(p) > 0) != ccw) std::reverse(p.begin(), p.end());
  std::rotate(p.begin(), p.begin() + canonical_start(p), p.end());
  return p;
}

std::vector<Vec2> resample_closed(const std::vector<Vec2>& polygon, const ResampleOptions& options) {
  const std::vector<Vec2> p = without_spikes(dedupe(polygon));
  const std::size_t n = p.size();
  if (n < 3 || !(options.edge > 0)) return p;
  std::vector<double> cum(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cum[i + 1] = cum[i] + norm(p[(i + 1) % n] - p[i]);
  const double total = cum[n];
  // Kept vertices: the first, and corners. The turning angle is measured at the scale of one edge
  // (points one edge back and ahead along the contour) so pixel staircases are not corners.
  std::vector<std::size_t> kept{0};
  const bool keep_all = options.corner_angle_deg <= 0.0;
  const double scale = std::min(options.edge, total / 6.0);
  // Turning angle of every input vertex at that scale, and the mean length of its two arms. A corner
  // must also turn strictly more than every other vertex within half an edge of it: on a tight bend
  // (radius below about an edge) every vertex turns past the limit, and keeping them all would leave
  // pieces far shorter than an edge (slivers against them); the bend is then sampled by the density below.
  std::vector<double> turning(n, 0.0), arm(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = point_at(p, cum, cum[i] - scale), b = p[i], c = point_at(p, cum, cum[i] + scale);
    const Vec2 u = b - a, w = c - b;
    const double nu = norm(u), nw = norm(w);
    if (!(nu > 0 && nw > 0)) continue;
    turning[i] = std::atan2(std::abs(cross(u, w)), dot(u, w));
    arm[i] = 0.5 * (nu + nw);
  }
  const double turn_limit = std::clamp(options.corner_angle_deg, 0.0, 180.0) * std::numbers::pi / 180.0;
  auto local_maximum = [&](std::size_t i) {
    for (int dir : {-1, 1})
      for (std::size_t k = 1; k < n; ++k) {
        const std::size_t j = (i + n + static_cast<std::size_t>(dir) * k) % n;
        double gap = std::abs(cum[j] - cum[i]);
        gap = std::min(gap, total - gap);
        if (gap >= 0.5 * scale) break;
        if (turning[j] >= turning[i]) return false;
      }
    return true;
  };
  for (std::size_t i = 1; i < n; ++i)
    if (keep_all || (turning[i] > turn_limit && local_maximum(i))) kept.push_back(i);
  // Point density (points per mm) at each input vertex: 1/edge on straight parts, more where the
  // contour bends so that the chord deviation e²κ/8 stays within the tolerance.
  std::vector<double> density(n, 1.0 / options.edge);
  if (options.tolerance > 0.0)
    for (std::size_t i = 0; i < n; ++i) {
      const double kappa = arm[i] > 0 ? turning[i] / arm[i] : 0.0;
      if (kappa <= 0) continue;
      const double spacing = std::clamp(std::sqrt(8.0 * options.tolerance / kappa), 0.5 * options.edge, options.edge);
      density[i] = 1.0 / spacing;
    }
  // Integrated density, trapezoids over the input edges.
  std::vector<double> phi(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    phi[i + 1] = phi[i] + 0.5 * (density[i] + density[(i + 1) % n]) * (cum[i + 1] - cum[i]);
  // Arc length at integrated density f (within [phi[i0], phi[i1]]), linear within each input edge.
  auto arc_at = [&](double f) {
    const std::size_t i = std::min<std::size_t>(
        n - 1, static_cast<std::size_t>(std::upper_bound(phi.begin(), phi.end(), f) - phi.begin()) - 1);
    const double span = phi[i + 1] - phi[i];
    const double t = span > 0 ? std::clamp((f - phi[i]) / span, 0.0, 1.0) : 0.0;
    return cum[i] + t * (cum[i + 1] - cum[i]);
  };
  std::vector<Vec2> out;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const double f0 = phi[kept[k]];
    const double f1 = k + 1 < kept.size() ? phi[kept[k + 1]] : phi[n];
    const int pieces = std::max(1, static_cast<int>(std::ceil(f1 - f0 - 1e-9)));
    out.push_back(p[kept[k]]);
    for (int j = 1; j < pieces; ++j) out.push_back(point_at(p, cum, arc_at(f0 + (f1 - f0) * j / pieces)));
  }
  return out;
}

}  // namespace c4d
