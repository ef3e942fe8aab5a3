// Triangle angle quality, Lim et al. 2014, "Vertex Correspondence and Mesh Quality" with Tables 3
// and 4: the share of angles within 40–80° ("good quality range") in 10° bins, and triangles
// containing an angle below 25° ("bad quality").
#include "contour4d/metrics/quality.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace c4d {
namespace {
// Angle at the corner between edges a and b, robust for nearly flat or needle corners.
double angle_deg(Vec3 a, Vec3 b) { return std::atan2(norm(cross(a, b)), dot(a, b)) * 180.0 / std::numbers::pi; }
}  // namespace

int angles_40_80(Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 p[3] = {a, b, c};
  if (!(norm(cross(b - a, c - a)) > 0.0)) return 0;
  int n = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = angle_deg(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
    n += d >= 40.0 && d < 80.0;
  }
  return n;
}

AngleQuality angle_quality(const TriangleMesh& mesh, const AngleQualityOptions& options) {
  AngleQuality q;
  std::size_t bins[4] = {0, 0, 0, 0};
  std::size_t angles = 0;
  double min_angle = 180.0, max_angle = 0.0;
  const std::size_t nv = mesh.positions.size();
  for (const Triangle& t : mesh.triangles) {
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) continue;
    const Vec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    ++q.triangles;
    const bool zero_area = !(norm(cross(p[1] - p[0], p[2] - p[0])) > 0.0);
    double tri_min = 180.0;
    for (int k = 0; k < 3; ++k) {
      // A zero-area triangle has angles 0, 0, 180 (or undefined); count it as 0 and 180.
      const double a = zero_area ? (k == 0 ? 180.0 : 0.0) : angle_deg(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
      ++angles;
      if (a >= 40.0 && a < 80.0) ++bins[std::min(3, static_cast<int>((a - 40.0) / 10.0))];
      tri_min = std::min(tri_min, a);
      max_angle = std::max(max_angle, a);
    }
    min_angle = std::min(min_angle, tri_min);
    if (tri_min < options.bad_angle_deg) ++q.bad_triangles;
  }
  if (angles == 0) return q;
  const double pct = 100.0 / static_cast<double>(angles);
  q.pct_40_50 = bins[0] * pct;
  q.pct_50_60 = bins[1] * pct;
  q.pct_60_70 = bins[2] * pct;
  q.pct_70_80 = bins[3] * pct;
  q.pct_40_80 = (bins[0] + bins[1] + bins[2] + bins[3]) * pct;
  q.bad_pct = 100.0 * static_cast<double>(q.bad_triangles) / static_cast<double>(q.triangles);
  q.min_angle_deg = min_angle;
  q.max_angle_deg = max_angle;
  return q;
}

}  // namespace c4d
