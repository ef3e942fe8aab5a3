// Lim et al. 2014, "Mesh Conformity" (the surface passes through every input contour), step 3c of our 4D
// morph (morph.cpp): coarse or pixel-traced contours keep sharp corners (frame 0's resampling keeps them),
// and a mesh whose vertices lie along the contour but not on the corner cuts it by up to a fraction of an
// edge (coarse real contours: a few mm between points, turning by up to about 120°).
#include "contour4d/motion/corner_snap.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace c4d {

std::size_t snap_corners(std::vector<Vec3>& x, const std::vector<std::vector<Vec3>>& lines,
                         const std::vector<std::vector<std::uint32_t>>& on_line, std::vector<char>& fixed,
                         const std::function<bool(std::uint32_t, Vec3)>& harmless, const CornerSnapOptions& opt) {
  const double cos_corner = std::cos(opt.corner_angle_deg * std::numbers::pi / 180.0);
  std::size_t moved = 0;
  for (std::size_t l = 0; l < lines.size() && l < on_line.size(); ++l) {
    if (on_line[l].empty()) continue;  // no vertex on this contour
    const std::vector<Vec3>& L = lines[l];
    const std::size_t n = L.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 a = L[k] - L[(k + n - 1) % n], b = L[(k + 1) % n] - L[k];
      const double la = norm(a), lb = norm(b);
      if (la <= 0 || lb <= 0 || dot(a, b) > cos_corner * la * lb) continue;  // turns less
      std::vector<std::pair<double, std::uint32_t>> near;
      auto consider = [&](std::uint32_t v) {
        const double d = distance(x[v], L[k]);
        if (d <= opt.reach) near.push_back({d, v});
      };
      if (opt.any_vertex)
        for (std::uint32_t v = 0; v < x.size(); ++v) consider(v);
      else
        for (std::uint32_t v : on_line[l]) consider(v);
      std::sort(near.begin(), near.end());
      for (std::size_t c = 0; c < std::min(near.size(), opt.tries); ++c) {
        const std::uint32_t v = near[c].second;
        if (fixed[v] || !harmless(v, L[k])) continue;
        x[v] = L[k];
        fixed[v] = 1;
        ++moved;
        break;
      }
    }
  }
  return moved;
}

}  // namespace c4d
