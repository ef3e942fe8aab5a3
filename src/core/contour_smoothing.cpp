// Smoothing traced contours within a tolerance (contour_smoothing.h). Lim et al. 2014 smooth the finished
// surface ("Surface Smoothing and Refinement", λ|μ); here the contours themselves are smoothed before any
// surface is built, so that every stage (one frame, all frames) sees the same smooth sections and the surface
// stays within a stated distance of what was traced.
//
// The spline: x = argmin Σ|x − p|² + λ Σ|Δ²x|² over a closed polygon is (I + λ D)x = p with D the circulant
// [1, −4, 6, −4, 1]; in the discrete Fourier basis it divides coefficient k by 1 + λ(2 − 2cos(2πk/n))², a
// low-pass filter that keeps the mean (k = 0) and shrinks the polygon only at second order. The area lost is
// given back by moving every point along its normal by the same distance.
#include "contour4d/core/contour_smoothing.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "contour4d/core/contour.h"

namespace c4d {
namespace {

using Complex = std::complex<double>;

// The discrete Fourier transform of the points as complex numbers (x + iy), O(n²) over a table of the n roots
// of unity (our contours have a few hundred points).
struct Spectrum {
  std::vector<Complex> roots;  // e^{2πi m/n}
  std::vector<Complex> coefficients;
};

Spectrum spectrum_of(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  Spectrum s;
  s.roots.resize(n);
  for (std::size_t m = 0; m < n; ++m) {
    const double a = 2.0 * std::numbers::pi * static_cast<double>(m) / static_cast<double>(n);
    s.roots[m] = {std::cos(a), std::sin(a)};
  }
  s.coefficients.assign(n, Complex{});
  for (std::size_t k = 0; k < n; ++k) {
    Complex sum{};
    for (std::size_t j = 0; j < n; ++j) sum += Complex{p[j].x, p[j].y} * std::conj(s.roots[(j * k) % n]);
    s.coefficients[k] = sum;
  }
  return s;
}

// The spline of stiffness λ: each coefficient divided by 1 + λ(2 − 2cos θ_k)², transformed back.
std::vector<Vec2> spline(const Spectrum& s, double lambda) {
  const std::size_t n = s.roots.size();
  std::vector<Complex> filtered(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double d = 2.0 - 2.0 * s.roots[k].real();
    filtered[k] = s.coefficients[k] / (1.0 + lambda * d * d);
  }
  std::vector<Vec2> x(n);
  for (std::size_t j = 0; j < n; ++j) {
    Complex sum{};
    for (std::size_t k = 0; k < n; ++k) sum += filtered[k] * s.roots[(j * k) % n];
    sum /= static_cast<double>(n);
    x[j] = {sum.real(), sum.imag()};
  }
  return x;
}

// Moves every point of x along its normal (the perpendicular of its two neighbours' chord) by one distance so
// that x's area becomes `area` (signed, of the input).
void keep_area(std::vector<Vec2>& x, double area) {
  const std::size_t n = x.size();
  double length = 0.0;
  for (std::size_t j = 0; j < n; ++j) length += norm(x[(j + 1) % n] - x[j]);
  if (length <= 0.0) return;
  const double grow = (std::abs(area) - std::abs(signed_area(x))) / length;
  const double side = signed_area(x) >= 0.0 ? 1.0 : -1.0;  // counter-clockwise: outward is the chord turned right
  std::vector<Vec2> out(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Vec2 t = x[(j + 1) % n] - x[(j + n - 1) % n];
    const double l = norm(t);
    const Vec2 outward = l > 0.0 ? Vec2{t.y, -t.x} * (side / l) : Vec2{};
    out[j] = x[j] + outward * grow;
  }
  x = std::move(out);
}

// Largest distance between a and b, both ways (each point of one to the other polygon).
double two_way_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double d = 0.0;
  for (const Vec2& p : a) d = std::max(d, polyline_distance(p, b));
  for (const Vec2& p : b) d = std::max(d, polyline_distance(p, a));
  return d;
}

constexpr int kAreaSteps = 4;

// The spline of stiffness λ with its area restored, or empty when it leaves the tolerance or crosses itself.
std::vector<Vec2> admissible(const Spectrum& s, const std::vector<Vec2>& p, double area, double lambda,
                             double tolerance) {
  std::vector<Vec2> x = spline(s, lambda);
  // The offset's own area (≈ π·distance²) makes one step fall short or overshoot: a few steps converge.
  for (int step = 0; step < kAreaSteps; ++step) keep_area(x, area);
  if (two_way_distance(p, x) > tolerance || is_self_intersecting(x)) return {};
  return x;
}

// The search for λ: 10^e for e in [kLowest, kHighest], bisected kSteps times.
constexpr double kLowestExponent = -2.0;
constexpr double kHighestExponent = 8.0;
constexpr int kSteps = 14;
constexpr std::size_t kMinPoints = 5;

}  // namespace

std::vector<Vec2> smooth_polygon(const std::vector<Vec2>& polygon, double tolerance_mm, double* stiffness) {
  if (stiffness != nullptr) *stiffness = 0.0;
  if (!(tolerance_mm > 0.0) || polygon.size() < kMinPoints) return polygon;
  const Spectrum s = spectrum_of(polygon);
  const double area = signed_area(polygon);
  std::vector<Vec2> best = admissible(s, polygon, area, std::pow(10.0, kLowestExponent), tolerance_mm);
  if (best.empty()) return polygon;
  double lo = kLowestExponent, hi = kHighestExponent;
  if (std::vector<Vec2> top = admissible(s, polygon, area, std::pow(10.0, hi), tolerance_mm); !top.empty()) {
    lo = hi;
    best = std::move(top);
  }
  for (int step = 0; step < kSteps && lo < hi; ++step) {
    const double mid = 0.5 * (lo + hi);
    if (std::vector<Vec2> x = admissible(s, polygon, area, std::pow(10.0, mid), tolerance_mm); !x.empty()) {
      lo = mid;
      best = std::move(x);
    } else {
      hi = mid;
    }
  }
  if (stiffness != nullptr) *stiffness = std::pow(10.0, lo);
  return best;
}

std::vector<ContourSmoothing> smooth_contours(Sequence& seq, double tolerance_mm) {
  std::vector<ContourSmoothing> out;
  if (!(tolerance_mm > 0.0)) return out;
  for (std::size_t f = 0; f < seq.frames.size(); ++f)
    for (Slice& slice : seq.frames[f].slices)
      for (std::size_t c = 0; c < slice.contours.size(); ++c) {
        std::vector<Vec3>& points = slice.contours[c].points;
        std::vector<Vec2> flat(points.size());
        for (std::size_t j = 0; j < points.size(); ++j) flat[j] = {dot(points[j], seq.u), dot(points[j], seq.v)};
        ContourSmoothing record{static_cast<int>(f), slice.id, static_cast<int>(c)};
        const std::vector<Vec2> smooth = smooth_polygon(flat, tolerance_mm, &record.stiffness);
        double sum = 0.0;
        for (std::size_t j = 0; j < points.size(); ++j) {
          const Vec2 move = smooth[j] - flat[j];
          points[j] = points[j] + seq.u * move.x + seq.v * move.y;
          const double d = polyline_distance(flat[j], smooth);
          sum += d;
        }
        record.moved_max_mm = two_way_distance(flat, smooth);
        record.moved_mean_mm = points.empty() ? 0.0 : sum / static_cast<double>(points.size());
        out.push_back(record);
      }
  return out;
}

}  // namespace c4d
