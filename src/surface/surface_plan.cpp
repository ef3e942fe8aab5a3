// The counts of one frame's surface fixed for every frame (surface_plan.h): Miara et al. §III.D (one base
// mesh, per-frame geometry), contours aligned by arc length from a matched start, cap interiors carried by
// mean-value coordinates (Hormann & Floater 2006, "Mean value coordinates for arbitrary planar polygons").
#include "contour4d/surface/surface_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace c4d {

namespace {

// Cumulative arc length at each vertex of a closed polygon (size n + 1; the last is the perimeter).
std::vector<double> arc_lengths(const std::vector<Vec2>& polygon) {
  const std::size_t n = polygon.size();
  std::vector<double> cum(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k) cum[k + 1] = cum[k] + norm(polygon[(k + 1) % n] - polygon[k]);
  return cum;
}

// The point at arc length s (0 ≤ s < perimeter) of the polygon.
Vec2 point_at(const std::vector<Vec2>& polygon, const std::vector<double>& cum, double s) {
  const std::size_t n = polygon.size();
  const auto it = std::upper_bound(cum.begin(), cum.end(), s);
  std::size_t seg = it == cum.begin() ? 0 : static_cast<std::size_t>(it - cum.begin()) - 1;
  seg = std::min(seg, n - 1);
  const double len = cum[seg + 1] - cum[seg];
  const double f = len > 0 ? (s - cum[seg]) / len : 0.0;
  return polygon[seg] + f * (polygon[(seg + 1) % n] - polygon[seg]);
}

// Correlation about the centroids of the polygon sampled from `start` with the centred reference.
double correlation(const std::vector<Vec2>& polygon, const std::vector<Vec2>& centred_ref, double start) {
  const std::vector<Vec2> s = resample_count(polygon, centred_ref.size(), start);
  const Vec2 c = mean_point(s);
  double sum = 0.0;
  for (std::size_t k = 0; k < s.size(); ++k) sum += dot(s[k] - c, centred_ref[k]);
  return sum;
}

}  // namespace

std::vector<Vec2> resample_count(const std::vector<Vec2>& polygon, std::size_t count, double start) {
  const std::vector<double> cum = arc_lengths(polygon);
  const double total = cum.back();
  std::vector<Vec2> out;
  out.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    double f = start + static_cast<double>(k) / static_cast<double>(count);
    f -= std::floor(f);
    out.push_back(point_at(polygon, cum, f * total));
  }
  return out;
}

std::vector<Vec2> aligned_samples(const std::vector<Vec2>& polygon, const std::vector<Vec2>& reference) {
  const std::size_t n = reference.size();
  if (n == 0 || polygon.size() < 2) return {};
  const Vec2 rc = mean_point(reference);
  std::vector<Vec2> ref(n);
  for (std::size_t k = 0; k < n; ++k) ref[k] = reference[k] - rc;
  // Coarse: every whole step of the samples (one resampling, cyclic shifts).
  const std::vector<Vec2> s = resample_count(polygon, n, 0.0);
  const Vec2 sc = mean_point(s);
  std::size_t best = 0;
  double best_score = -std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < n; ++j) {
    double score = 0.0;
    for (std::size_t k = 0; k < n; ++k) score += dot(s[(k + j) % n] - sc, ref[k]);
    if (score > best_score) {
      best_score = score;
      best = j;
    }
  }
  // Fine: golden-section search within a step either side.
  const double step = 1.0 / static_cast<double>(n);
  double lo = static_cast<double>(best) * step - step, hi = static_cast<double>(best) * step + step;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  double fa = correlation(polygon, ref, a), fb = correlation(polygon, ref, b);
  for (int it = 0; it < 24; ++it) {
    if (fa > fb) {
      hi = b;
      b = a;
      fb = fa;
      a = hi - g * (hi - lo);
      fa = correlation(polygon, ref, a);
    } else {
      lo = a;
      a = b;
      fa = fb;
      b = lo + g * (hi - lo);
      fb = correlation(polygon, ref, b);
    }
  }
  double start = 0.5 * (lo + hi);
  // Never worse than the best whole step.
  if (correlation(polygon, ref, start) < best_score) start = static_cast<double>(best) * step;
  return resample_count(polygon, n, start - std::floor(start));
}

std::vector<double> mean_value_weights(Vec2 x, const std::vector<std::vector<Vec2>>& loops) {
  std::vector<double> w;
  for (const auto& loop : loops) {
    const std::size_t n = loop.size();
    std::vector<double> tan_half(n);  // tan(α_k / 2), α_k the signed angle at x from point k to point k + 1
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2 a = loop[k] - x, b = loop[(k + 1) % n] - x;
      const double denom = norm(a) * norm(b) + dot(a, b);
      tan_half[k] = denom > 1e-300 ? cross(a, b) / denom : 0.0;
    }
    for (std::size_t k = 0; k < n; ++k) {
      const double r = norm(loop[k] - x);
      w.push_back(r > 1e-300 ? (tan_half[(k + n - 1) % n] + tan_half[k]) / r : 0.0);
    }
  }
  double sum = 0.0;
  for (double v : w) sum += v;
  if (std::abs(sum) > 1e-300)
    for (double& v : w) v /= sum;
  return w;
}

Vec2 mean_point(const std::vector<Vec2>& points) {
  Vec2 c;
  for (const Vec2& p : points) c = c + p;
  return points.empty() ? c : (1.0 / static_cast<double>(points.size())) * c;
}

std::array<double, 3> barycentric(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1), d20 = dot(d, e0), d21 = dot(d, e1);
  const double den = d00 * d11 - d01 * d01;
  if (!(std::abs(den) > 1e-300)) return {1.0, 0.0, 0.0};
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  return {1.0 - v - w, v, w};
}

}  // namespace c4d
