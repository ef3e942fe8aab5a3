// Lim et al. 2014, "Mesh Conformity" (the surface passes through the input contours, measured every
// 0.2 mm along them) and "4D Morphing of the Heart Model" (the morphed mesh must fit each frame's
// contours): a last fit of a morphed frame onto its contours. Gauss–Newton rounds: each contour sample
// finds its closest mesh point (CGAL AABB tree); near the samples that are off the mesh, vertex
// displacements D solve the regularised least squares
//   Σ_samples |Σ_k b_k D_{v_k} − (p − q)|² + α² |L D|² + β² |D|²
// (b: barycentric weights of the closest point q in its triangle, L: uniform Laplacian with the
// vertices outside the moving region held at zero), one sparse LDLT factorisation for the three
// coordinates (Eigen).
#include "contour4d/motion/contour_fit.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "contour4d/core/contour.h"
#include "contour4d/core/sparse_solve.h"
#include "contour4d/metrics/surface_projector.h"

namespace c4d {
namespace {

// Barycentric weights of p (on or near triangle abc) clamped to the triangle.
std::array<double, 3> barycentric(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(std::abs(den) > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den, u = 1.0 - v - w;
  u = std::max(0.0, u);
  v = std::max(0.0, v);
  w = std::max(0.0, w);
  const double s = u + v + w;
  return s > 0 ? std::array<double, 3>{u / s, v / s, w / s} : std::array<double, 3>{1.0 / 3, 1.0 / 3, 1.0 / 3};
}

}  // namespace

std::vector<Vec3> contour_fit_samples(const std::vector<std::vector<Vec3>>& contours, double step) {
  std::vector<Vec3> samples;
  for (const std::vector<Vec3>& c : contours) {
    if (c.size() < 2) continue;
    const std::vector<Vec3> s = sample_closed_polyline(c, step);
    samples.insert(samples.end(), s.begin(), s.end());
  }
  return samples;
}

ContourFitReport fit_to_contours(std::vector<Vec3>& x, const std::vector<Triangle>& triangles,
                                 const std::vector<std::vector<Vec3>>& contours, const std::vector<char>& fixed,
                                 const ContourFitOptions& opt) {
  return fit_to_points(x, triangles, contour_fit_samples(contours, opt.step_mm), fixed, opt);
}

ContourFitReport fit_to_points(std::vector<Vec3>& x, const std::vector<Triangle>& triangles,
                               const std::vector<Vec3>& samples, const std::vector<char>& fixed,
                               const ContourFitOptions& opt, std::vector<std::int32_t>* sample_triangles) {
  ContourFitReport rep;
  const std::size_t nv = x.size(), ns = samples.size();
  if (ns == 0 || triangles.empty() || nv == 0) return rep;
  std::vector<std::vector<std::uint32_t>> nb;  // one-rings, built once a region has to move
  std::vector<char> moved(nv, 0);
  std::vector<Vec3> closest(ns);
  const bool warm = sample_triangles != nullptr && sample_triangles->size() == ns;
  std::vector<std::int32_t> tri_of = warm ? *sample_triangles : std::vector<std::int32_t>(ns, -1);
  for (int it = 0; it <= std::max(0, opt.iterations); ++it) {
    {
      const SurfaceProjector proj(TriangleMesh{x, triangles});
      if (proj.empty()) return rep;
      // Later rounds (and a first round given an earlier call's answers) walk from the triangle each sample
      // landed on (the mesh moved only near the far samples). A first round without them walks each sample
      // from the answer of the sample before it in a fixed block of 64 (the samples follow the contours,
      // 0.2 mm apart), each block's first from the block before's first (those in sequence; the very first
      // from triangle 0). A walk that ends too far searches the tree from where it ended
      // (SurfaceProjector::walk), never from scratch. The blocks do not depend on the thread count.
      constexpr std::size_t block = 64;
      const std::size_t blocks = (ns + block - 1) / block;
      const bool cold = it == 0 && !warm;
      auto search = [&](std::size_t s) {
        std::int32_t hint = proj.hint_of(tri_of[s]);
        closest[s] = proj.walk(samples[s], nullptr, &hint);
        tri_of[s] = proj.mesh_triangle(hint);
      };
      if (cold)
        for (std::size_t b = 0; b < blocks; ++b) {
          tri_of[b * block] = b == 0 ? proj.mesh_triangle(0) : tri_of[(b - 1) * block];
          search(b * block);
        }
      tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        for (std::size_t s = b * block + (cold ? 1 : 0); s < std::min(ns, (b + 1) * block); ++s) {
          if (cold) tri_of[s] = tri_of[s - 1];
          search(s);
        }
      });
    }
    double worst = 0;
    std::vector<char> region(nv, 0);
    bool any = false;
    for (std::size_t s = 0; s < ns; ++s) {
      const double d = distance(samples[s], closest[s]);
      if (!(d <= opt.reach_mm) || tri_of[s] < 0) continue;
      worst = std::max(worst, d);
      if (d <= opt.tolerance_mm) continue;
      for (std::uint32_t v : triangles[static_cast<std::size_t>(tri_of[s])]) region[v] = 1;
      any = true;
    }
    if (it == 0) rep.max_before_mm = worst;
    rep.max_after_mm = worst;
    if (!any || it == opt.iterations) break;
    if (nb.empty()) nb = vertex_neighbours(nv, triangles);
    for (int ring = 0; ring < opt.rings; ++ring) {
      std::vector<char> grown = region;
      for (std::size_t v = 0; v < nv; ++v)
        if (region[v])
          for (std::uint32_t w : nb[v]) grown[w] = 1;
      region.swap(grown);
    }
    std::vector<int> col(nv, -1);
    int m = 0;
    for (std::size_t v = 0; v < nv; ++v)
      if (region[v] && !(v < fixed.size() && fixed[v])) col[v] = m++;
    if (m == 0) break;

    std::vector<Eigen::Triplet<double>> at;  // sample rows
    std::vector<Vec3> rhs;
    for (std::size_t s = 0; s < ns; ++s) {
      if (tri_of[s] < 0) continue;
      const Triangle& t = triangles[static_cast<std::size_t>(tri_of[s])];
      if (col[t[0]] < 0 && col[t[1]] < 0 && col[t[2]] < 0) continue;
      if (!(distance(samples[s], closest[s]) <= opt.reach_mm)) continue;
      const std::array<double, 3> b = barycentric(closest[s], x[t[0]], x[t[1]], x[t[2]]);
      const int row = static_cast<int>(rhs.size());
      for (std::size_t k = 0; k < 3; ++k)
        if (col[t[k]] >= 0 && b[k] > 0) at.emplace_back(row, col[t[k]], b[k]);
      rhs.push_back(samples[s] - closest[s]);
    }
    std::vector<Eigen::Triplet<double>> lt;  // Laplacian rows, one per moving vertex
    for (std::size_t v = 0; v < nv; ++v) {
      if (col[v] < 0) continue;
      lt.emplace_back(col[v], col[v], 1.0);
      const double w = nb[v].empty() ? 0.0 : -1.0 / static_cast<double>(nb[v].size());
      for (std::uint32_t u : nb[v])
        if (col[u] >= 0) lt.emplace_back(col[v], col[u], w);
    }
    using Sparse = Eigen::SparseMatrix<double>;
    Sparse A(static_cast<Eigen::Index>(rhs.size()), m), L(m, m), I(m, m);
    A.setFromTriplets(at.begin(), at.end());
    L.setFromTriplets(lt.begin(), lt.end());
    I.setIdentity();
    const Sparse M = Sparse(A.transpose() * A) + opt.smoothness * opt.smoothness * Sparse(L.transpose() * L) +
                     opt.damping * opt.damping * I;
    Eigen::MatrixXd R(static_cast<Eigen::Index>(rhs.size()), 3);
    for (std::size_t r = 0; r < rhs.size(); ++r) {
      const auto row = static_cast<Eigen::Index>(r);
      R(row, 0) = rhs[r].x;
      R(row, 1) = rhs[r].y;
      R(row, 2) = rhs[r].z;
    }
    SparseLdlt solver;
    if (!factor_lower(solver, M)) break;
    const Eigen::MatrixXd D = ldlt_solve(solver, Eigen::MatrixXd(A.transpose() * R));
    if (!D.allFinite()) break;
    for (std::size_t v = 0; v < nv; ++v)
      if (col[v] >= 0) {
        const auto r = static_cast<Eigen::Index>(col[v]);
        x[v] = x[v] + Vec3{D(r, 0), D(r, 1), D(r, 2)};
        moved[v] = 1;
      }
  }
  rep.moved = static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
  if (sample_triangles) *sample_triangles = std::move(tri_of);
  return rep;
}

}  // namespace c4d
