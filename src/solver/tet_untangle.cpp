// Untangling and smoothing a tetrahedral mesh by node-by-node optimisation: J. M. Escobar, E. Rodríguez,
// R. Montenegro, G. Montero, J. M. González-Yuste, "Simultaneous untangling and smoothing of tetrahedral meshes",
// CMAME 192 (2003). Each tet's distortion is K = |S|²_F / (3 h(σ)^(2/3)) with S its edge matrix times the inverse
// of its reference edge matrix (a target-matrix shape measure, P. Knupp), σ = det S and
// h(σ) = (σ + √(σ² + 4δ²)) / 2, which equals σ for valid tets when δ = 0 and stays positive for inverted ones, so
// one smooth objective carries a node out of an inverted star and then keeps its tets from flattening.
#include "contour4d/solver/tet_untangle.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "contour4d/metrics/tet_quality.h"

namespace c4d {
namespace {

Eigen::Matrix3d edge_matrix(const std::vector<Vec3>& x, const Tet& q) {
  const Vec3 e1 = x[q[1]] - x[q[0]], e2 = x[q[2]] - x[q[0]], e3 = x[q[3]] - x[q[0]];
  Eigen::Matrix3d a;
  a << e1.x, e2.x, e3.x, e1.y, e2.y, e3.y, e1.z, e2.z, e3.z;
  return a;
}

bool bad_tet(const std::vector<Vec3>& x, const Tet& q, double max_aspect) {
  return !(tet_volume(x[q[0]], x[q[1]], x[q[2]], x[q[3]]) > 0.0) ||
         !(tet_aspect_ratio(x[q[0]], x[q[1]], x[q[2]], x[q[3]]) <= max_aspect);
}

struct Objective {
  const std::vector<Tet>& tets;
  const NodeStars& stars;
  const std::vector<Eigen::Matrix3d>& target_inverse;  // per tet: its reference edge matrix, inverted

  // The smallest σ over v's star.
  double min_sigma(const std::vector<Vec3>& x, std::uint32_t v) const {
    double m = HUGE_VAL;
    for (std::uint32_t i = stars.offsets[v]; i < stars.offsets[v + 1]; ++i) {
      const std::uint32_t t = stars.stars[i];
      m = std::min(m, (edge_matrix(x, tets[t]) * target_inverse[t]).determinant());
    }
    return m;
  }
  // Σ K over v's star, and its gradient with respect to x[v] when `gradient` is given. With g the row of W⁻¹
  // that x[v] enters S by (S = A W⁻¹; minus the sum of the rows for a tet's first node): ∇|S|² = 2 S g and
  // ∇σ = cof(S) g, cof(S) = σ S⁻ᵀ = [s₁×s₂, s₂×s₀, s₀×s₁], and ∇K = K (∇|S|² / |S|² − ⅔ h′(σ) ∇σ / h).
  double value(const std::vector<Vec3>& x, std::uint32_t v, double delta, Eigen::Vector3d* gradient) const {
    double f = 0.0;
    if (gradient) gradient->setZero();
    for (std::uint32_t i = stars.offsets[v]; i < stars.offsets[v + 1]; ++i) {
      const std::uint32_t t = stars.stars[i];
      const Eigen::Matrix3d s = edge_matrix(x, tets[t]) * target_inverse[t];
      const double sigma = s.determinant(), root = std::sqrt(sigma * sigma + 4.0 * delta * delta);
      const double h = 0.5 * (sigma + root), frobenius = s.squaredNorm();
      const double k = frobenius / (3.0 * std::cbrt(h * h));
      f += k;
      if (!gradient || !(frobenius > 0.0) || !(root > 0.0)) continue;
      const Tet& q = tets[t];
      const int corner = static_cast<int>(std::find(q.begin(), q.end(), v) - q.begin());
      const Eigen::Vector3d g = corner == 0 ? Eigen::Vector3d(-target_inverse[t].colwise().sum().transpose())
                                            : Eigen::Vector3d(target_inverse[t].row(corner - 1).transpose());
      Eigen::Matrix3d cofactor;
      cofactor.col(0) = s.col(1).cross(s.col(2));
      cofactor.col(1) = s.col(2).cross(s.col(0));
      cofactor.col(2) = s.col(0).cross(s.col(1));
      *gradient += k * (2.0 * (s * g) / frobenius - (2.0 / 3.0) / root * (cofactor * g));
    }
    return f;
  }
};

// Steepest descent on one node (backtracking steps from a tenth of its longest edge), until a step gains less
// than kConverged of the objective.
void relax_node(std::vector<Vec3>& x, std::uint32_t v, const Objective& objective, const UntangleOptions& o) {
  constexpr double kConverged = 1e-5;
  double edge = 0.0;
  for (std::uint32_t i = objective.stars.offsets[v]; i < objective.stars.offsets[v + 1]; ++i)
    for (std::uint32_t u : objective.tets[objective.stars.stars[i]]) edge = std::max(edge, norm(x[u] - x[v]));
  if (!(edge > 0.0)) return;
  for (int step = 0; step < o.node_steps; ++step) {
    const double sigma = objective.min_sigma(x, v);
    const double delta = sigma < o.epsilon ? std::sqrt(o.epsilon * (o.epsilon - sigma)) : 0.0;
    const Vec3 p = x[v];
    Eigen::Vector3d g;
    const double f0 = objective.value(x, v, delta, &g);
    const Vec3 grad{g.x(), g.y(), g.z()};
    const double length = norm(grad);
    if (!(length > 0.0)) return;
    double f1 = f0;
    for (double t = 0.1 * edge; t > 1e-7 * edge; t *= 0.5) {
      x[v] = p - (t / length) * grad;
      f1 = objective.value(x, v, delta, nullptr);
      if (f1 < f0) break;
    }
    if (!(f1 < f0)) {
      x[v] = p;
      return;
    }
    if (f0 - f1 < kConverged * f0) return;
  }
}

}  // namespace

NodeStars node_stars(std::size_t node_count, const std::vector<Tet>& tets) {
  NodeStars s;
  s.offsets.assign(node_count + 1, 0);
  for (const Tet& q : tets)
    for (std::uint32_t v : q) ++s.offsets[v + 1];
  for (std::size_t v = 0; v < node_count; ++v) s.offsets[v + 1] += s.offsets[v];
  s.stars.resize(s.offsets.back());
  std::vector<std::uint32_t> fill(s.offsets.begin(), s.offsets.end() - 1);
  for (std::uint32_t t = 0; t < tets.size(); ++t)
    for (std::uint32_t v : tets[t]) s.stars[fill[v]++] = t;
  return s;
}

std::size_t untangle_tets(std::vector<Vec3>& x, const std::vector<Vec3>& reference, const std::vector<Tet>& tets,
                          std::size_t fixed_nodes, const NodeStars& stars, const UntangleOptions& options) {
  std::vector<char> free(x.size(), 0);
  for (const Tet& q : tets)
    if (bad_tet(x, q, options.max_aspect))
      for (std::uint32_t v : q)
        if (v >= fixed_nodes) free[v] = 1;
  if (std::find(free.begin(), free.end(), 1) == free.end()) return 0;
  // The reference shapes, inverted, of the tets the free region touches (computed as the region grows).
  std::vector<Eigen::Matrix3d> target_inverse(tets.size());
  std::vector<char> targeted(tets.size(), 0);
  const Objective objective{tets, stars, target_inverse};
  std::vector<char> moved(x.size(), 0);
  bool inverted = true;
  for (int sweep = 0; sweep < options.sweeps; ++sweep) {
    // While a tet stays inverted, the free region grows by one ring of tets.
    if (inverted) {
      std::vector<char> grown = free;
      for (std::size_t v = fixed_nodes; v < x.size(); ++v)
        if (free[v])
          for (std::uint32_t i = stars.offsets[v]; i < stars.offsets[v + 1]; ++i)
            for (std::uint32_t u : tets[stars.stars[i]])
              if (u >= fixed_nodes) grown[u] = 1;
      free.swap(grown);
      for (std::size_t v = fixed_nodes; v < x.size(); ++v)
        if (free[v])
          for (std::uint32_t i = stars.offsets[v]; i < stars.offsets[v + 1]; ++i) {
            const std::uint32_t t = stars.stars[i];
            if (!targeted[t]) target_inverse[t] = edge_matrix(reference, tets[t]).inverse();
            targeted[t] = 1;
          }
    }
    for (std::size_t v = fixed_nodes; v < x.size(); ++v)
      if (free[v]) {
        relax_node(x, static_cast<std::uint32_t>(v), objective, options);
        moved[v] = 1;
      }
    bool flat = false;
    inverted = false;
    for (const Tet& q : tets) {
      if (!(tet_volume(x[q[0]], x[q[1]], x[q[2]], x[q[3]]) > 0.0)) {
        inverted = flat = true;
        break;
      }
      flat = flat || bad_tet(x, q, options.max_aspect);
    }
    if (!inverted && (!flat || sweep + 1 >= options.quality_sweeps)) break;
  }
  return static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
}

}  // namespace c4d
