// Volumes from contours by Simpson's method of discs, the clinical reference for the mesh volume,
// and the ejection fraction EF = (EDV − ESV) / EDV of a volume curve.
//
// Rule used (stated in docs/evaluate.md): slice i, at offset h_i along the stack normal, encloses
// area A_i (outer contours minus holes). Its disc thickness is t_i = (h_{i+1} − h_{i−1}) / 2, with
// t_0 = h_1 − h_0 and t_last = h_last − h_{last−1}: each disc reaches halfway to its neighbours and
// the end discs as far beyond their plane as inside. Evenly spaced slices give the textbook
// V = spacing × Σ A_i. The trapezoid volume Σ (A_i + A_{i+1}) / 2 × (h_{i+1} − h_i) stops at the
// first and last planes, like a mesh capped flat there.
#include "contour4d/metrics/volume.h"

#include <algorithm>
#include <cmath>

#include "contour4d/core/contour.h"

namespace c4d {
namespace {
std::vector<Vec2> project(const std::vector<Vec3>& pts, Vec3 u, Vec3 v) {
  std::vector<Vec2> out;
  out.reserve(pts.size());
  for (const Vec3& p : pts) out.push_back({dot(p, u), dot(p, v)});
  return out;
}

// Even-odd point in polygon.
bool inside(const std::vector<Vec2>& poly, Vec2 q) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 a = poly[i], b = poly[j];
    if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

double slice_offset(const Slice& s, Vec3 normal) {
  double sum = 0.0;
  std::size_t n = 0;
  for (const Contour& c : s.contours)
    for (const Vec3& p : c.points) {
      sum += dot(p, normal);
      ++n;
    }
  return n > 0 ? sum / static_cast<double>(n) : s.offset;
}

std::vector<double> thickness(const std::vector<SliceArea>& s, double fallback) {
  const std::size_t n = s.size();
  std::vector<double> t(n, fallback);
  if (n < 2) return t;
  for (std::size_t i = 0; i < n; ++i) {
    const double below = i > 0 ? s[i].offset - s[i - 1].offset : s[1].offset - s[0].offset;
    const double above = i + 1 < n ? s[i + 1].offset - s[i].offset : s[n - 1].offset - s[n - 2].offset;
    t[i] = 0.5 * (below + above);
  }
  return t;
}
}  // namespace

double enclosed_area(const Slice& slice, Vec3 u, Vec3 v, double* outer_area) {
  std::vector<std::vector<Vec2>> polys;
  for (const Contour& c : slice.contours)
    if (c.points.size() >= 3) polys.push_back(project(c.points, u, v));
  double area = 0.0, outer = 0.0;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    // Depth: how many other contours hold this one. Contours of one slice do not cross, so one of
    // its vertices decides (its centroid would not: it may lie outside a non-convex contour).
    int depth = 0;
    for (std::size_t j = 0; j < polys.size(); ++j)
      if (j != i && inside(polys[j], polys[i][0])) ++depth;
    const double a = std::abs(signed_area(polys[i]));
    area += depth % 2 == 0 ? a : -a;
    if (depth % 2 == 0) outer += a;
  }
  if (outer_area) *outer_area = outer;
  return area;
}

std::vector<DiscVolume> simpson_volumes(const Sequence& seq) {
  std::vector<DiscVolume> out(seq.frames.size());
  std::vector<double> gaps;
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    DiscVolume& d = out[f];
    for (const Slice& s : seq.frames[f].slices) {
      SliceArea a{s.id, slice_offset(s, seq.normal), 0.0, 0.0};
      a.area = enclosed_area(s, seq.u, seq.v, &a.outer_area);
      d.slices.push_back(a);
    }
    std::stable_sort(d.slices.begin(), d.slices.end(),
                     [](const SliceArea& a, const SliceArea& b) { return a.offset < b.offset; });
    for (std::size_t i = 1; i < d.slices.size(); ++i) gaps.push_back(d.slices[i].offset - d.slices[i - 1].offset);
  }
  double median_gap = 0.0;
  if (!gaps.empty()) {
    std::sort(gaps.begin(), gaps.end());
    median_gap = gaps[gaps.size() / 2];
  }
  for (DiscVolume& d : out) {
    const std::vector<double> t = thickness(d.slices, median_gap);
    for (std::size_t i = 0; i < d.slices.size(); ++i) {
      d.volume += d.slices[i].area * t[i];
      d.outer_volume += d.slices[i].outer_area * t[i];
    }
    for (std::size_t i = 1; i < d.slices.size(); ++i)
      d.trapezoid_volume +=
          0.5 * (d.slices[i].area + d.slices[i - 1].area) * (d.slices[i].offset - d.slices[i - 1].offset);
  }
  return out;
}

EjectionFraction ejection_fraction(const std::vector<double>& volumes) {
  EjectionFraction ef;
  if (volumes.empty()) return ef;
  ef.ed_frame = static_cast<int>(std::max_element(volumes.begin(), volumes.end()) - volumes.begin());
  ef.es_frame = static_cast<int>(std::min_element(volumes.begin(), volumes.end()) - volumes.begin());
  ef.edv = volumes[ef.ed_frame];
  ef.esv = volumes[ef.es_frame];
  ef.ef_pct = ef.edv > 0.0 ? 100.0 * (ef.edv - ef.esv) / ef.edv : 0.0;
  return ef;
}

}  // namespace c4d
