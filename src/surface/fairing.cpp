// Fairing: Lim et al. 2014, "Surface Smoothing and Refinement" (eq. 7) smooths the tiled surface
// with λ|μ|ε passes and upsamples it with quartic Bézier patches. We reach the same goal (a smooth
// surface through the contours) with one discrete thin-plate solve (Kobbelt et al. 1998, "Interactive
// multi-resolution modeling on arbitrary meshes"; Botsch & Sorkine 2008, "On linear variational
// surface deformation methods"): the free vertices minimise the squared umbrella Laplacian, the
// contour vertices are fixed, and because the Laplacian of each contour vertex enters the energy the
// two sides of a contour are coupled, giving a surface that is smooth across it. Where a region
// meshed coarser meets the rest (ring caps), its terms use the scale-dependent umbrella of
// Desbrun et al. 1999 ("Implicit fairing of irregular meshes using diffusion and curvature flow", §4),
// so that the slopes, not the steps, match across the contour (FairingOptions::scale_aware).
#include "contour4d/surface/fairing.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "contour4d/core/sparse_solve.h"

namespace c4d {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The normal equations LfᵀLf x = Lfᵀ(−c) of the rows `trip` (Lf, rows × nf, listed row by row) and
// their constants: the lower triangle of LfᵀLf (all the factorisation reads) and the right-hand side,
// each entry summed in Eigen's order for `Lfᵀ * Lf` and `Lfᵀ * rhs` (rows of Lf in increasing order,
// each term Lf(k, i)·Lf(k, j) or Lf(k, i)·rhs(k)): the same values to the bit, without forming Lf, its
// transpose and the full product. The matrix goes into `a` (nf × nf), the right-hand side into `rhs`.
void normal_equations(const std::vector<Eigen::Triplet<double>>& trip,
                      const std::vector<std::array<double, 3>>& constant, int rows, int nf, Sparse& a,
                      Eigen::MatrixXd& rhs) {
  std::vector<std::size_t> row_start(static_cast<std::size_t>(rows) + 1, 0);
  for (const auto& e : trip) ++row_start[static_cast<std::size_t>(e.row()) + 1];
  for (std::size_t r = 0; r < static_cast<std::size_t>(rows); ++r) row_start[r + 1] += row_start[r];
  std::vector<std::size_t> col_start(static_cast<std::size_t>(nf) + 1, 0);
  for (const auto& e : trip) ++col_start[static_cast<std::size_t>(e.col()) + 1];
  for (std::size_t c = 0; c < static_cast<std::size_t>(nf); ++c) col_start[c + 1] += col_start[c];
  std::vector<std::size_t> col_items(trip.size());  // per column, its entries (indices into trip) by row
  {
    std::vector<std::size_t> fill(col_start.begin(), col_start.end() - 1);
    for (std::size_t k = 0; k < trip.size(); ++k) col_items[fill[static_cast<std::size_t>(trip[k].col())]++] = k;
  }
  a.resize(nf, nf);
  {
    std::vector<int> outer(static_cast<std::size_t>(nf) + 1, 0), inner, touched;
    std::vector<double> values, sum(static_cast<std::size_t>(nf), 0.0);
    std::vector<char> seen(static_cast<std::size_t>(nf), 0);
    inner.reserve(12 * static_cast<std::size_t>(nf));
    values.reserve(12 * static_cast<std::size_t>(nf));
    for (int j = 0; j < nf; ++j) {
      touched.clear();
      for (std::size_t c = col_start[static_cast<std::size_t>(j)]; c < col_start[static_cast<std::size_t>(j) + 1];
           ++c) {
        const auto& ej = trip[col_items[c]];
        const double y = ej.value();
        for (std::size_t e = row_start[static_cast<std::size_t>(ej.row())];
             e < row_start[static_cast<std::size_t>(ej.row()) + 1]; ++e) {
          const int i = trip[e].col();
          if (i < j) continue;
          const auto ui = static_cast<std::size_t>(i);
          if (!seen[ui]) {
            seen[ui] = 1;
            sum[ui] = trip[e].value() * y;
            touched.push_back(i);
          } else {
            sum[ui] += trip[e].value() * y;
          }
        }
      }
      std::sort(touched.begin(), touched.end());
      for (int i : touched) {
        inner.push_back(i);
        values.push_back(sum[static_cast<std::size_t>(i)]);
        seen[static_cast<std::size_t>(i)] = 0;
      }
      outer[static_cast<std::size_t>(j) + 1] = static_cast<int>(inner.size());
    }
    a.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
    std::copy(outer.begin(), outer.end(), a.outerIndexPtr());
    std::copy(inner.begin(), inner.end(), a.innerIndexPtr());
    std::copy(values.begin(), values.end(), a.valuePtr());
  }
  rhs = Eigen::MatrixXd::Zero(nf, 3);
  for (Eigen::Index k = 0; k < 3; ++k)
    for (int r = 0; r < rows; ++r) {
      const double b = -constant[static_cast<std::size_t>(r)][static_cast<std::size_t>(k)];
      for (std::size_t e = row_start[static_cast<std::size_t>(r)]; e < row_start[static_cast<std::size_t>(r) + 1]; ++e)
        rhs(trip[e].col(), k) += trip[e].value() * b;
    }
}

}  // namespace

bool fair_thin_plate(TriangleMesh& mesh, const std::vector<char>& fixed, const std::vector<char>& keep_shape,
                     const FairingOptions& options) {
  const std::size_t nv = mesh.positions.size();
  if (nv == 0) return true;
  // One-ring neighbours (sorted, unique; CSR) and boundary flags: each triangle lists its two other
  // corners at each corner, so a neighbour listed once shares an edge used by one triangle.
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) start[v + 1] += 2;
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> listed(start.back());
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const Triangle& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) {
        listed[fill[t[k]]++] = t[(k + 1) % 3];
        listed[fill[t[k]]++] = t[(k + 2) % 3];
      }
  }
  std::vector<char> boundary(nv, 0);
  std::vector<std::uint32_t> ring_start(nv + 1, 0), ring_list;
  ring_list.reserve(listed.size() / 2 + nv);
  for (std::size_t v = 0; v < nv; ++v) {
    const auto first = listed.begin() + start[v], last = listed.begin() + start[v + 1];
    std::sort(first, last);
    for (auto it = first; it != last;) {
      auto same = it;
      while (same != last && *same == *it) ++same;
      if (same - it == 1) boundary[v] = boundary[*it] = 1;
      ring_list.push_back(*it);
      it = same;
    }
    ring_start[v + 1] = static_cast<std::uint32_t>(ring_list.size());
  }
  auto ring_size = [&](std::size_t v) { return ring_start[v + 1] - ring_start[v]; };
  // Unknown index of each free vertex.
  std::vector<int> unknown(nv, -1);
  int nf = 0;
  for (std::size_t v = 0; v < nv; ++v)
    if ((fixed.empty() || !fixed[v]) && ring_size(v) > 0) unknown[v] = nf++;
  if (nf == 0) return true;

  // Rows of the energy: for each used, non-boundary vertex v, sqrt(w_v) (L(x)_v − b_v), split into
  // the part on the unknowns (matrix Lf) and a constant (fixed neighbours and b_v).
  std::vector<Eigen::Triplet<double>> trip;
  std::vector<std::array<double, 3>> constant;
  trip.reserve(8 * nv);
  constant.reserve(nv);
  int rows = 0;
  const bool scale_ok = std::isfinite(options.reference_edge) && options.reference_edge > 0.0;
  std::vector<double> ring_weight;  // a scale-aware vertex's neighbour weights, in ring order
  for (std::size_t v = 0; v < nv; ++v) {
    if (ring_size(v) == 0 || boundary[v]) continue;
    const bool shape = !keep_shape.empty() && keep_shape[v];
    double w = shape ? std::sqrt(std::max(0.0, options.shape_weight)) : 1.0;
    if (!options.row_scale.empty()) w *= options.row_scale[v];
    const double inv = 1.0 / static_cast<double>(ring_size(v));
    // Neighbour weights: 1/n (uniform), or 1/n · reference_edge / |x_u − x_v| (scale-aware, where every
    // edge has a usable length; a vertex on top of a neighbour keeps the uniform term).
    bool scaled = !options.scale_aware.empty() && options.scale_aware[v] && scale_ok;
    if (scaled) {
      ring_weight.clear();
      for (std::uint32_t k = ring_start[v]; k < ring_start[v + 1] && scaled; ++k) {
        const double d = distance(mesh.positions[v], mesh.positions[ring_list[k]]);
        scaled = d > 1e-6 * options.reference_edge;
        ring_weight.push_back(inv * (options.reference_edge / d));
      }
    }
    auto weight = [&](std::uint32_t k) { return scaled ? ring_weight[k - ring_start[v]] : inv; };  // k: ring_list index
    double self = -1.0;
    if (scaled) {
      self = 0.0;
      for (const double wk : ring_weight) self -= wk;
    }
    std::array<double, 3> c{0, 0, 0};
    bool touches = false;
    auto add = [&](std::uint32_t u, double coef) {
      if (unknown[u] >= 0) {
        trip.emplace_back(rows, unknown[u], w * coef);
        touches = true;
      } else {
        const Vec3 p = mesh.positions[u];
        c[0] += w * coef * p.x;
        c[1] += w * coef * p.y;
        c[2] += w * coef * p.z;
      }
    };
    const std::size_t mark = trip.size();
    for (std::uint32_t k = ring_start[v]; k < ring_start[v + 1]; ++k) add(ring_list[k], weight(k));
    add(static_cast<std::uint32_t>(v), self);
    if (!touches) {
      trip.resize(mark);
      continue;
    }
    if (shape) {
      // b_v: the Laplacian of the input positions.
      Vec3 lap = self * mesh.positions[v];
      for (std::uint32_t k = ring_start[v]; k < ring_start[v + 1]; ++k) lap += weight(k) * mesh.positions[ring_list[k]];
      c[0] -= w * lap.x;
      c[1] -= w * lap.y;
      c[2] -= w * lap.z;
    }
    constant.push_back(c);
    ++rows;
  }
  Sparse a;
  Eigen::MatrixXd rhs;
  normal_equations(trip, constant, rows, nf, a, rhs);
  SparseLdlt solver;
  if (!factor_lower(solver, a)) return false;
  const Eigen::MatrixXd x = ldlt_solve(solver, rhs);
  if (!x.allFinite()) return false;
  // A singular system (a free part without fixed vertex) shows as a tiny pivot.
  const auto [smallest, largest] = solver.pivot_range();
  if (solver.size() > 0 && smallest <= 1e-12 * std::max(1.0, largest)) return false;
  for (std::size_t v = 0; v < nv; ++v)
    if (unknown[v] >= 0) mesh.positions[v] = {x(unknown[v], 0), x(unknown[v], 1), x(unknown[v], 2)};
  return true;
}

}  // namespace c4d
