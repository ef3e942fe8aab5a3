#pragma once
// Test helper: distance from a point to an axis-aligned ellipse, by dense sampling refined by bisection.
#include <cmath>
#include <numbers>

namespace c4d::test {

//! Distance (same unit as the inputs) from (x, y) to the ellipse x²/a² + y²/b² = 1, to about 1e-9.
inline double ellipse_distance_aligned(double a, double b, double x, double y, int samples = 1000) {
  double best = 1e300, bt = 0;
  for (int i = 0; i < samples; ++i) {
    const double t = 2 * std::numbers::pi * i / samples;
    const double d = std::hypot(a * std::cos(t) - x, b * std::sin(t) - y);
    if (d < best) best = d, bt = t;
  }
  for (double h = 2 * std::numbers::pi / samples; h > 1e-9; h *= 0.5)
    for (double t : {bt - h, bt + h}) {
      const double d = std::hypot(a * std::cos(t) - x, b * std::sin(t) - y);
      if (d < best) best = d, bt = t;
    }
  return best;
}

}  // namespace c4d::test
