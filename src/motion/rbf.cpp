// Lim et al. 2014, "4D Morphing of the Heart Model", eq. 9: Hardy multiquadric RBF interpolation,
// c per source point from its nearest neighbour; 10 sub-steps against crossing motion paths.
// We add an optional affine term (Buhmann, "Radial Basis Functions", 2003, §2) so that rigid motion is
// reproduced exactly, which the deformation's rigid-motion invariance relies on.
#include "contour4d/motion/rbf.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include "contour4d/core/errors.h"
#include "simd/packed_math_internal.h"
#include "rbf_lanes_internal.h"
#include "simd_avx_internal.h"

namespace c4d {

RbfDeformer::RbfDeformer(const std::vector<Vec3>& src, const std::vector<Vec3>& dst, const RbfOptions& options)
    : centers_(src), affine_(options.affine) {
  const std::size_t n = src.size();
  if (n == 0 || dst.size() != n)
    throw SolverError(ErrorCode::Internal, {}, "RbfDeformer: source and target sizes differ");
  // Sources with nothing to fit against: pure translation.
  c2_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j)
      if (j != k) best = std::min(best, distance(src[j], src[k]));
    const double c = std::max(options.min_c, std::isfinite(best) ? options.c_scale * best : 1.0);
    c2_[k] = c * c;
  }
  const std::size_t m = affine_ ? 4 : 0;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n + m), static_cast<Eigen::Index>(n + m));
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n + m), 3);
  for (std::size_t j = 0; j < n; ++j) {
    const auto J = static_cast<Eigen::Index>(j);
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 d = src[j] - src[k];
      A(J, static_cast<Eigen::Index>(k)) = std::sqrt(dot(d, d) + c2_[k]);
    }
    if (affine_) {
      const Eigen::Index N = static_cast<Eigen::Index>(n);
      A(J, N) = 1;
      A(J, N + 1) = src[j].x;
      A(J, N + 2) = src[j].y;
      A(J, N + 3) = src[j].z;
      A(N, J) = 1;
      A(N + 1, J) = src[j].x;
      A(N + 2, J) = src[j].y;
      A(N + 3, J) = src[j].z;
    }
    const Vec3 disp = dst[j] - src[j];
    b(J, 0) = disp.x;
    b(J, 1) = disp.y;
    b(J, 2) = disp.z;
  }
  // Partial pivoting (blocked, fast); the affine block makes the system indefinite and singular
  // for coplanar sources, which the residual check turns into a clear error.
  const Eigen::MatrixXd x = A.partialPivLu().solve(b);
  const double residual = (A * x - b).norm(), scale = std::max(1.0, b.norm());
  if (!std::isfinite(residual) || !x.allFinite() || residual > 1e-6 * scale || x.cwiseAbs().maxCoeff() > 1e12)
    throw SolverError(ErrorCode::Internal, {}, "RBF system is singular (sources coplanar or duplicated)",
                      "Add an off-plane source point (the paper's far point)");
  weights_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto K = static_cast<Eigen::Index>(k);
    weights_[k] = {x(K, 0), x(K, 1), x(K, 2)};
  }
  if (affine_) {
    const Eigen::Index N = static_cast<Eigen::Index>(n);
    a0_ = {x(N, 0), x(N, 1), x(N, 2)};
    ax_ = {x(N + 1, 0), x(N + 1, 1), x(N + 1, 2)};
    ay_ = {x(N + 2, 0), x(N + 2, 1), x(N + 2, 2)};
    az_ = {x(N + 3, 0), x(N + 3, 1), x(N + 3, 2)};
  }
}

Vec3 RbfDeformer::apply(Vec3 p) const {
  Vec3 out = p;
  // Two centres' square roots per instruction (simd/packed_math_internal.h: the same bits); the sum keeps their order.
  const std::size_t n = centers_.size();
  std::size_t k = 0;
  for (; k + 1 < n; k += 2) {
    const Vec3 d0 = p - centers_[k], d1 = p - centers_[k + 1];
    double r[2];
    detail::sqrt2(dot(d0, d0) + c2_[k], dot(d1, d1) + c2_[k + 1], r);
    out += r[0] * weights_[k];
    out += r[1] * weights_[k + 1];
  }
  if (k < n) {
    const Vec3 d = p - centers_[k];
    out += std::sqrt(dot(d, d) + c2_[k]) * weights_[k];
  }
  return with_affine(p, out);
}

Vec3 RbfDeformer::with_affine(Vec3 p, Vec3 sum) const {
  if (affine_) sum += a0_ + p.x * ax_ + p.y * ay_ + p.z * az_;
  return sum;
}

void RbfDeformer::apply(std::vector<Vec3>& points) const {
  // Each point on its own, four (AVX) or two (SSE2) per instruction, each lane summing the centres in
  // apply(p)'s order (rbf_lanes_internal.h): the same result on any number of threads and any CPU.
#if defined(__SSE2__)
  static const bool quad = detail::avx_available();
  const std::size_t groups = points.size() / 4;
  tbb::parallel_for(std::size_t(0), groups, [&](std::size_t g) {
    Vec3 in[4];
    const Vec3* from[4];
    Vec3* to[4];
    for (std::size_t k = 0; k < 4; ++k) {
      in[k] = points[4 * g + k];
      from[k] = &in[k];
      to[k] = &points[4 * g + k];
    }
    if (quad) {
      detail::rbf_quad(centers_.data(), c2_.data(), weights_.data(), centers_.size(), from, to);
    } else {
      detail::rbf_lanes<detail::Sse2Lanes>(centers_.data(), c2_.data(), weights_.data(), centers_.size(), from, to);
      detail::rbf_lanes<detail::Sse2Lanes>(centers_.data(), c2_.data(), weights_.data(), centers_.size(), from + 2,
                                           to + 2);
    }
    for (std::size_t k = 0; k < 4; ++k) *to[k] = with_affine(in[k], *to[k]);
  });
  for (std::size_t i = 4 * groups; i < points.size(); ++i) points[i] = apply(points[i]);
#else
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) { points[i] = apply(points[i]); });
#endif
}

void deform_rbf(std::vector<Vec3>& points, const std::vector<Vec3>& src, const std::vector<Vec3>& dst, int steps,
                const RbfOptions& options) {
  steps = std::max(1, steps);
  std::vector<Vec3> from = src;
  for (int s = 1; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    std::vector<Vec3> to(src.size());
    for (std::size_t k = 0; k < src.size(); ++k) to[k] = src[k] + t * (dst[k] - src[k]);
    RbfDeformer(from, to, options).apply(points);
    from = std::move(to);
  }
}

}  // namespace c4d
