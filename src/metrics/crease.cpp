// Crease angles along the contours (crease.h): the check that a surface built through contours is as smooth on
// them as between them (Lim et al. 2014 smooth the surface so that "the contour lines" do not show; here it is
// measured, per class of edge, as the 95th percentile of the angle between the two triangles' normals).
#include "contour4d/metrics/crease.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "metrics_internal.h"

namespace c4d {
namespace {

// The plane each vertex lies in (index into `offsets`), or -1.
std::vector<int> plane_of_vertices(const TriangleMesh& mesh, Vec3 normal, const std::vector<double>& offsets,
                                   double tolerance) {
  std::vector<int> plane(mesh.positions.size(), -1);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const double h = dot(mesh.positions[v], normal);
    const auto it = std::lower_bound(offsets.begin(), offsets.end(), h - tolerance);
    if (it != offsets.end() && *it <= h + tolerance) plane[v] = static_cast<int>(it - offsets.begin());
  }
  return plane;
}

Vec3 facet_normal(const std::vector<Vec3>& x, const Triangle& t) {
  return normalized(cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]));
}

double p95(std::vector<double>& a) {
  if (a.empty()) return 0.0;
  std::sort(a.begin(), a.end());
  return metrics_internal::percentile(a, 0.95);
}

// Calls visit(lo, hi, angle, t0, t1) for every edge shared by exactly two triangles t0 < t1 with area, the
// angle between their normals in degrees. Triangles with an invalid index are skipped (topology.h reports them).
template <class Visit>
void for_each_interior_edge(const TriangleMesh& mesh, const Visit& visit) {
  std::vector<std::array<std::uint32_t, 3>> edges;  // (lo, hi, triangle), sorted: a run of two is an interior edge
  edges.reserve(3 * mesh.triangles.size());
  const std::size_t nv = mesh.positions.size();
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(f)});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
    if (j - i == 2) {
      const double angle = metrics_internal::angle_deg(facet_normal(mesh.positions, mesh.triangles[edges[i][2]]),
                                                       facet_normal(mesh.positions, mesh.triangles[edges[i + 1][2]]));
      if (std::isfinite(angle)) visit(edges[i][0], edges[i][1], angle, edges[i][2], edges[i + 1][2]);
    }
    i = j;
  }
}

}  // namespace

CreaseAngles crease_angles(const TriangleMesh& mesh, const Sequence& seq, const Frame& frame, double tolerance_mm) {
  std::vector<double> offsets;
  for (const Slice& s : frame.slices) offsets.push_back(s.offset);
  std::sort(offsets.begin(), offsets.end());
  const std::vector<int> plane = plane_of_vertices(mesh, seq.normal, offsets, tolerance_mm);
  const int last = static_cast<int>(offsets.size()) - 1;

  std::vector<double> on, ends, between;
  for_each_interior_edge(mesh, [&](std::uint32_t lo, std::uint32_t hi, double angle, std::uint32_t, std::uint32_t) {
    const int pa = plane[lo], pb = plane[hi];
    if (pa >= 0 && pa == pb) {
      on.push_back(angle);
      if (pa == 0 || pa == last) ends.push_back(angle);
    } else if (pa < 0 && pb < 0) {
      between.push_back(angle);
    }
  });
  CreaseAngles r;
  r.on_contours = on.size();
  r.on_ends = ends.size();
  r.between = between.size();
  r.on_contours_p95 = p95(on);
  r.on_ends_p95 = p95(ends);
  r.between_p95 = p95(between);
  return r;
}

std::vector<std::array<std::uint32_t, 2>> neighbour_pairs(const TriangleMesh& mesh) {
  std::vector<std::array<std::uint32_t, 2>> pairs;
  for_each_interior_edge(mesh, [&](std::uint32_t, std::uint32_t, double, std::uint32_t t0, std::uint32_t t1) {
    pairs.push_back({t0, t1});
  });
  return pairs;
}

Fold sharpest_fold(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                   const std::vector<std::array<std::uint32_t, 2>>& pairs) {
  Fold fold;
  for (const auto& [t0, t1] : pairs) {
    const double angle =
        metrics_internal::angle_deg(facet_normal(positions, triangles[t0]), facet_normal(positions, triangles[t1]));
    if (angle > fold.angle_deg) fold = {angle, t0, t1};
  }
  return fold;
}

Fold sharpest_fold(const TriangleMesh& mesh) {
  return sharpest_fold(mesh.positions, mesh.triangles, neighbour_pairs(mesh));
}

}  // namespace c4d
