// λ|μ|ε smoothing: Lim et al. 2014, "Surface Smoothing and Refinement", eq. 7 and the normal-plane
// error bound; Taubin 1995 ("A signal processing approach to fair surface design") for λ|μ with
// pass band k_PB = 1/λ + 1/μ; vertex normals after Max 1999 ("Weights for computing vertex
// normals from facet normals").
#include "contour4d/surface/smoothing.h"

#include <algorithm>
#include <cmath>

namespace c4d {

std::vector<Vec3> vertex_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> n(mesh.positions.size());
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = mesh.positions[t[k]];
      const Vec3 e1 = mesh.positions[t[(k + 1) % 3]] - p, e2 = mesh.positions[t[(k + 2) % 3]] - p;
      const double w = dot(e1, e1) * dot(e2, e2);
      if (w > 0) n[t[k]] += cross(e1, e2) / w;
    }
  for (Vec3& v : n) v = normalized(v);
  return n;
}

void smooth_lambda_mu_epsilon(TriangleMesh& mesh, const std::vector<char>& fixed, const SmoothingOptions& options) {
  const std::size_t nv = mesh.positions.size();
  if (nv == 0 || options.iterations <= 0) return;
  // One-ring neighbours (unique, sorted: the sums do not depend on triangle order beyond rounding).
  const auto ring = vertex_neighbours(nv, mesh.triangles);
  const double lambda = options.lambda;
  const double mu = 1.0 / (options.pass_band - 1.0 / lambda);
  std::vector<Vec3> next(nv);
  for (int it = 0; it < options.iterations; ++it)
    for (double f : {lambda, mu}) {
      const std::vector<Vec3> normal = vertex_normals(mesh);
      for (std::size_t i = 0; i < nv; ++i) {
        const Vec3 p = mesh.positions[i];
        next[i] = p;
        if ((!fixed.empty() && fixed[i]) || ring[i].empty()) continue;
        Vec3 avg{};
        for (std::uint32_t j : ring[i]) avg += mesh.positions[j];
        avg = avg / static_cast<double>(ring[i].size());
        Vec3 q = f * (avg - p);
        const double d = std::abs(dot(q, normal[i]));
        if (options.epsilon > 0 && d > options.epsilon) q = (options.epsilon / d) * q;
        next[i] = p + q;
      }
      mesh.positions.swap(next);
    }
}

}  // namespace c4d
