#pragma once
//! \file rbf.h
//! \brief Radial basis function deformation with Hardy multiquadrics (Lim et al., "4D Morphing of the
//! Heart Model", eq. 9): maps source points exactly onto target points and moves everything else smoothly.

#include <vector>

#include "contour4d/core/vec.h"

namespace c4d {

//! Options of the RBF interpolant.
struct RbfOptions {
  bool affine = true;    //!< add an affine term (exact for rigid and affine motion; the paper has none)
  double c_scale = 1.0;  //!< c_k = c_scale × distance from source k to its nearest other source (mm)
  double min_c = 1e-3;   //!< lower bound of c_k (mm), for coincident sources
};

//! f(x) = x + Σ_k w_k φ_k(|x − x_k|) (+ a + A x), φ_k(r) = sqrt(r² + c_k²), fitted so that f(src_k) = dst_k.
//! Factor once, apply to many points (STYLE.md rule 5).
class RbfDeformer {
 public:
  //! \pre src.size() == dst.size() >= 1. Duplicate sources must have equal targets.
  //! \throw SolverError when the system is singular (e.g. all sources coplanar with the affine term:
  //! then add an off-plane source, as the paper's "far point").
  RbfDeformer(const std::vector<Vec3>& src, const std::vector<Vec3>& dst, const RbfOptions& options = {});

  //! The deformed position of p (mm).
  Vec3 apply(Vec3 p) const;
  //! Deforms every point in place (several points per SIMD instruction where the CPU allows; each point's
  //! result is apply(p)'s, bit for bit).
  void apply(std::vector<Vec3>& points) const;

 private:
  //! The affine term added to `sum`, the point p plus its multiquadric sum.
  Vec3 with_affine(Vec3 p, Vec3 sum) const;

  std::vector<Vec3> centers_;
  std::vector<double> c2_;
  std::vector<Vec3> weights_;
  Vec3 a0_{};
  Vec3 ax_{}, ay_{}, az_{};  //!< columns of A: f adds ax·x + ay·y + az·z
  bool affine_ = true;
};

//! Moves `points` from `src` to `dst` through `steps` equal sub-steps, each its own RBF, so that
//! motion paths are less likely to cross (the paper uses 10).
void deform_rbf(std::vector<Vec3>& points, const std::vector<Vec3>& src, const std::vector<Vec3>& dst, int steps = 10,
                const RbfOptions& options = {});

}  // namespace c4d
