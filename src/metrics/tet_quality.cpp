// Tetrahedron quality: the smallest dihedral angle (between the outward normals n_i, n_j of two faces the angle is
// π − ∠(n_i, n_j)) and Verdict's aspect ratio (C. J. Stimpson, C. D. Ernst, P. Knupp, P. P. Pébay, D. Thompson,
// "The Verdict geometric quality library", SAND2007-1751, 2007: h_max / (2√6 r), r = 3V / Σ face areas).
#include "contour4d/metrics/tet_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace c4d {
namespace {

// The four outward area vectors (twice the face areas) of a positively oriented tet, faces opposite a, b, c, d.
void face_normals(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Vec3 n[4]) {
  n[0] = cross(c - b, d - b);  // opposite a: (b, c, d)
  n[1] = cross(d - a, c - a);  // opposite b: (a, d, c)
  n[2] = cross(b - a, d - a);  // opposite c: (a, b, d)
  n[3] = cross(c - a, b - a);  // opposite d: (a, c, b)
}

}  // namespace

double tet_min_dihedral_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Vec3 n[4];
  face_normals(a, b, c, d, n);
  double len[4];
  for (int i = 0; i < 4; ++i) len[i] = norm(n[i]);
  double max_cos = -1.0;  // cos of the dihedral angle = −cos ∠(n_i, n_j); the smallest angle has the largest cos
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (len[i] > 0.0 && len[j] > 0.0) max_cos = std::max(max_cos, -dot(n[i], n[j]) / (len[i] * len[j]));
  return std::acos(std::clamp(max_cos, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

double tet_aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double v = tet_volume(a, b, c, d);
  if (!(v > 0.0)) return std::numeric_limits<double>::infinity();
  Vec3 n[4];
  face_normals(a, b, c, d, n);
  const double area = 0.5 * (norm(n[0]) + norm(n[1]) + norm(n[2]) + norm(n[3]));
  const double h2 = std::max({dot(b - a, b - a), dot(c - a, c - a), dot(d - a, d - a), dot(c - b, c - b),
                              dot(d - b, d - b), dot(d - c, d - c)});
  const double inradius = 3.0 * v / area;
  return std::sqrt(h2) / (2.0 * std::sqrt(6.0) * inradius);
}

TetQuality measure_tets(const std::vector<Vec3>& x, const std::vector<Tet>& tets) {
  TetQuality q;
  q.min_volume_mm3 = std::numeric_limits<double>::infinity();
  double max_cos = -1.0;
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const Vec3 &a = x[tets[t][0]], &b = x[tets[t][1]], &c = x[tets[t][2]], &d = x[tets[t][3]];
    const Vec3 ab = b - a, ac = c - a, ad = d - a;
    const double v = dot(cross(ab, ac), ad) / 6.0;
    q.volume_mm3 += v;
    q.min_volume_mm3 = std::min(q.min_volume_mm3, v);
    if (!(v > 0.0)) {
      if (q.inverted++ == 0) q.first_inverted = t;
      continue;
    }
    Vec3 n[4];
    face_normals(a, b, c, d, n);
    double len[4];
    for (int i = 0; i < 4; ++i) len[i] = norm(n[i]);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) max_cos = std::max(max_cos, -dot(n[i], n[j]) / (len[i] * len[j]));
    const double h2 =
        std::max({dot(ab, ab), dot(ac, ac), dot(ad, ad), dot(c - b, c - b), dot(d - b, d - b), dot(d - c, d - c)});
    const double inradius = 3.0 * v / (0.5 * (len[0] + len[1] + len[2] + len[3]));
    const double aspect = std::sqrt(h2) / (2.0 * std::sqrt(6.0) * inradius);
    if (aspect > q.max_aspect_ratio) {
      q.max_aspect_ratio = aspect;
      q.worst_aspect_tet = t;
    }
  }
  if (tets.empty()) q.min_volume_mm3 = 0.0;
  q.min_dihedral_deg = std::acos(std::clamp(max_cos, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  return q;
}

}  // namespace c4d
