// A multi-right-hand-side solve with Eigen's SimplicialLDLT factor (Eigen 3.4, SimplicialCholesky.h
// _solve_impl and SparseCore/TriangularSolver.h), for the linear systems of the surface fairing, the 4D
// morph's projection and the contour fit.
#include "contour4d/core/sparse_solve.h"

#include <utility>

namespace c4d {

Eigen::MatrixXd solve_ldlt(const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& solver, const Eigen::MatrixXd& b) {
  using SparseMatrix = Eigen::SparseMatrix<double>;
  using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Index n = b.rows(), nc = b.cols();
  const SparseMatrix& L = solver.matrixL().nestedExpression();
  const Eigen::VectorXd& d = solver.vectorD();
  const auto& P = solver.permutationP();
  Rows y(n, nc);  // the columns side by side: one row per unknown
  if (P.size() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) y.row(P.indices()(i)) = b.row(i);
  } else {
    y = b;
  }
  // Column i of L: its entries below the (unit) diagonal, as Eigen's iterators visit them.
  const int* outer = L.outerIndexPtr();
  const int* inner = L.innerIndexPtr();
  const int* counts = L.innerNonZeroPtr();  // null when compressed
  const double* value = L.valuePtr();
  auto below = [&](Eigen::Index i) {
    Eigen::Index k = outer[i];
    const Eigen::Index end = counts ? k + counts[i] : outer[i + 1];
    while (k < end && inner[k] <= i) ++k;
    return std::pair<Eigen::Index, Eigen::Index>(k, end);
  };
  double* Y = y.data();
  if (L.nonZeros() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) {  // L y = y, column i of L scattered (UnitLower, column-major)
      const auto [k0, k1] = below(i);
      const double* t = Y + i * nc;
      bool all = true;
      for (Eigen::Index c = 0; c < nc; ++c) all = all && t[c] != 0.0;
      if (all && nc == 3) {  // the usual case: x, y and z together
        const double t0 = t[0], t1 = t[1], t2 = t[2];
        for (Eigen::Index k = k0; k < k1; ++k) {
          double* r = Y + static_cast<Eigen::Index>(inner[k]) * 3;
          r[0] -= t0 * value[k];
          r[1] -= t1 * value[k];
          r[2] -= t2 * value[k];
        }
        continue;
      }
      for (Eigen::Index c = 0; c < nc; ++c) {
        const double tc = t[c];
        if (tc == 0.0) continue;  // Eigen skips a zero (so that −0 stays −0)
        for (Eigen::Index k = k0; k < k1; ++k) Y[static_cast<Eigen::Index>(inner[k]) * nc + c] -= tc * value[k];
      }
    }
  }
  if (d.size() > 0)
    for (Eigen::Index i = 0; i < n; ++i) {
      const double inv = 1.0 / d(i);
      for (Eigen::Index c = 0; c < nc; ++c) Y[i * nc + c] = inv * Y[i * nc + c];
    }
  if (L.nonZeros() > 0) {
    for (Eigen::Index i = n - 1; i >= 0; --i) {  // Lᵀ y = y, column i of L gathered (UnitUpper, row-major)
      const auto [k0, k1] = below(i);
      double* t = Y + i * nc;
      if (nc == 3) {
        double t0 = t[0], t1 = t[1], t2 = t[2];
        for (Eigen::Index k = k0; k < k1; ++k) {
          const double* r = Y + static_cast<Eigen::Index>(inner[k]) * 3;
          t0 -= value[k] * r[0];
          t1 -= value[k] * r[1];
          t2 -= value[k] * r[2];
        }
        t[0] = t0;
        t[1] = t1;
        t[2] = t2;
        continue;
      }
      for (Eigen::Index c = 0; c < nc; ++c) {
        double tc = t[c];
        for (Eigen::Index k = k0; k < k1; ++k) tc -= value[k] * Y[static_cast<Eigen::Index>(inner[k]) * nc + c];
        t[c] = tc;
      }
    }
  }
  Eigen::MatrixXd x(n, nc);
  if (P.size() > 0) {
    const auto& Pinv = solver.permutationPinv();
    for (Eigen::Index i = 0; i < n; ++i) x.row(Pinv.indices()(i)) = y.row(i);
  } else {
    x = y;
  }
  return x;
}

}  // namespace c4d
