// Tiling between two contours of adjacent slices: Lim et al. 2014, "Reconstruction from Segmented
// Contour Lines" (after Barequet & Sharir 1996). We tile each connected pair with the optimal
// band of Fuchs, Kedem & Uselton 1977 (shortest spanning edges, dynamic programming): every
// triangle has vertices on both slices, so none is flat and no collapsed pair can form. Branching
// (1→n, n→1) merges the n contours into one chain through bridges whose interior is lifted towards
// the other slice (Meyers, Skinner & Sloan 1992), which yields the saddle of the paper's ridge.
#include "contour4d/surface/tiling.h"

#include <cmath>
#include <limits>

namespace c4d {

std::vector<Triangle> tile_chains(const std::vector<std::uint32_t>& lower, const std::vector<std::uint32_t>& upper,
                                  const std::vector<Vec3>& positions) {
  const std::size_t n = lower.size(), m = upper.size();
  std::vector<Triangle> out;
  if (n == 0 || m == 0) return out;
  std::size_t j0 = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < m; ++j) {
    const double d = distance(positions[lower[0]], positions[upper[j]]);
    if (d < best) {
      best = d;
      j0 = j;
    }
  }
  auto L = [&](std::size_t i) { return lower[i % n]; };
  auto U = [&](std::size_t j) { return upper[(j0 + j) % m]; };
  auto len = [&](std::uint32_t a, std::uint32_t b) { return distance(positions[a], positions[b]); };
  const std::size_t W = m + 1;
  std::vector<double> cost((n + 1) * W, std::numeric_limits<double>::infinity());
  std::vector<char> from((n + 1) * W, 0);  // 1: came by advancing lower, 2: by advancing upper
  cost[0] = 0.0;
  for (std::size_t i = 0; i <= n; ++i)
    for (std::size_t j = 0; j <= m; ++j) {
      const double c = cost[i * W + j];
      if (i < n) {
        const double nc = c + len(L(i + 1), U(j));
        if (nc < cost[(i + 1) * W + j]) {
          cost[(i + 1) * W + j] = nc;
          from[(i + 1) * W + j] = 1;
        }
      }
      if (j < m) {
        const double nc = c + len(L(i), U(j + 1));
        if (nc < cost[i * W + j + 1]) {
          cost[i * W + j + 1] = nc;
          from[i * W + j + 1] = 2;
        }
      }
    }
  std::size_t i = n, j = m;
  out.reserve(n + m);
  while (i > 0 || j > 0) {
    if (from[i * W + j] == 1) {
      --i;
      out.push_back({L(i), L(i + 1), U(j)});
    } else {
      --j;
      out.push_back({L(i), U(j + 1), U(j)});
    }
  }
  return out;
}

std::vector<std::uint32_t> bridge_chains(const std::vector<std::uint32_t>& a, std::size_t x_at,
                                         const std::vector<std::uint32_t>& b, std::size_t y_at,
                                         const std::vector<std::uint32_t>& bridge) {
  std::vector<std::uint32_t> out;
  out.reserve(a.size() + b.size() + 2 * bridge.size() + 2);
  for (std::size_t k = 0; k <= x_at; ++k) out.push_back(a[k]);
  out.insert(out.end(), bridge.begin(), bridge.end());
  for (std::size_t k = 0; k <= b.size(); ++k) out.push_back(b[(y_at + k) % b.size()]);
  out.insert(out.end(), bridge.rbegin(), bridge.rend());
  for (std::size_t k = x_at; k < a.size(); ++k) out.push_back(a[k]);
  return out;
}

}  // namespace c4d
