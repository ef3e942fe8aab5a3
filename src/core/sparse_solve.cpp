// A multi-right-hand-side solve with Eigen's SimplicialLDLT factor (Eigen 3.4, SimplicialCholesky.h
// _solve_impl and SparseCore/TriangularSolver.h), for the linear systems of the surface fairing, the 4D
// morph's projection and the contour fit.
#include "contour4d/core/sparse_solve.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace c4d {

namespace {

// y = L⁻ᵀ D⁻¹ L⁻¹ y for the rows of y (nc columns side by side); NC > 0 fixes nc at compile time (x, y and
// z: the compiler keeps the three in registers; a run-time count of 3 took 2.5× as long).
template <int NC>
void substitute(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& d, double* Y, Eigen::Index n,
                Eigen::Index runtime_nc) {
  const Eigen::Index nc = NC > 0 ? NC : runtime_nc;
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
  // Row i's entries in a local copy, so that they stay in registers while other rows are written.
  std::array<double, (NC > 0 ? NC : 1)> fixed{};
  std::vector<double> dynamic(NC > 0 ? 0 : static_cast<std::size_t>(nc));
  double* t = NC > 0 ? fixed.data() : dynamic.data();
  if (L.nonZeros() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) {  // L y = y, column i of L scattered (UnitLower, column-major)
      const auto [k0, k1] = below(i);
      // Eigen skips a column whose entry is zero (so that −0 stays −0); usually none is.
      bool zero = false;
      for (Eigen::Index c = 0; c < nc; ++c) {
        t[c] = Y[i * nc + c];
        zero = zero || t[c] == 0.0;
      }
      for (Eigen::Index k = k0; k < k1; ++k) {
        double* r = Y + static_cast<Eigen::Index>(inner[k]) * nc;
        if (!zero) {
          for (Eigen::Index c = 0; c < nc; ++c) r[c] -= t[c] * value[k];
        } else {
          for (Eigen::Index c = 0; c < nc; ++c)
            if (t[c] != 0.0) r[c] -= t[c] * value[k];
        }
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
      for (Eigen::Index c = 0; c < nc; ++c) t[c] = Y[i * nc + c];
      for (Eigen::Index k = k0; k < k1; ++k) {
        const double* r = Y + static_cast<Eigen::Index>(inner[k]) * nc;
        for (Eigen::Index c = 0; c < nc; ++c) t[c] -= value[k] * r[c];
      }
      for (Eigen::Index c = 0; c < nc; ++c) Y[i * nc + c] = t[c];
    }
  }
}

// x = P⁻¹ L⁻ᵀ D⁻¹ L⁻¹ P b (SimplicialLDLT::_solve_impl's order; P empty: none).
template <class Perm>
Eigen::MatrixXd permuted_solve(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& d, const Perm& P,
                               const Perm& Pinv, const Eigen::MatrixXd& b) {
  using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Index n = b.rows(), nc = b.cols();
  Rows y(n, nc);  // the columns side by side: one row per unknown
  if (P.size() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) y.row(P.indices()(i)) = b.row(i);
  } else {
    y = b;
  }
  if (nc == 3)
    substitute<3>(L, d, y.data(), n, nc);
  else
    substitute<0>(L, d, y.data(), n, nc);
  Eigen::MatrixXd x(n, nc);
  if (P.size() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) x.row(Pinv.indices()(i)) = y.row(i);
  } else {
    x = y;
  }
  return x;
}

}  // namespace

Eigen::MatrixXd solve_ldlt(const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& solver, const Eigen::MatrixXd& b) {
  return permuted_solve(solver.matrixL().nestedExpression(), solver.vectorD(), solver.permutationP(),
                        solver.permutationPinv(), b);
}

bool SparseLdlt::compute(const Eigen::SparseMatrix<double>& a) {
  using Sparse = Eigen::SparseMatrix<double>;
  const Eigen::Index n = a.cols();
  // The full symmetric pattern of the lower triangle, each column sorted: column j gets the rows k < j
  // of the earlier columns that hold (j, k) (in increasing k), then its own entries i >= j (increasing).
  // Eigen's ordering step builds the same pattern as C + Cᵀ, C the full symmetric copy.
  std::vector<int> count(static_cast<std::size_t>(n) + 1, 0);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Sparse::InnerIterator it(a, j); it; ++it)
      if (it.row() >= j) {
        ++count[static_cast<std::size_t>(j) + 1];
        if (it.row() > j) ++count[static_cast<std::size_t>(it.row()) + 1];
      }
  for (Eigen::Index j = 0; j < n; ++j) count[static_cast<std::size_t>(j) + 1] += count[static_cast<std::size_t>(j)];
  Sparse symm(n, n);
  symm.resizeNonZeros(count.back());
  std::copy(count.begin(), count.end(), symm.outerIndexPtr());
  {
    std::vector<int> fill(count.begin(), count.end() - 1);
    int* inner = symm.innerIndexPtr();
    double* value = symm.valuePtr();
    for (Eigen::Index j = 0; j < n; ++j)
      for (Sparse::InnerIterator it(a, j); it; ++it) {
        const auto i = static_cast<int>(it.row());
        if (i < j) continue;
        value[fill[static_cast<std::size_t>(j)]] = 0.0;
        inner[fill[static_cast<std::size_t>(j)]++] = i;
        if (i > j) {
          value[fill[static_cast<std::size_t>(i)]] = 0.0;
          inner[fill[static_cast<std::size_t>(i)]++] = static_cast<int>(j);
        }
      }
  }
  // Eigen's AMDOrdering hands its minimum-degree routine the same pattern: the same permutation.
  Eigen::internal::minimum_degree_ordering(symm, pinv_);
  p_ = pinv_.inverse();
  Sparse ap(n, n);
  ap.selfadjointView<Eigen::Upper>() = a.selfadjointView<Eigen::Lower>().twistedBy(p_);
  ldlt_.compute(ap);
  return ldlt_.info() == Eigen::Success;
}

Eigen::MatrixXd SparseLdlt::solve(const Eigen::MatrixXd& b) const {
  return permuted_solve(ldlt_.matrixL().nestedExpression(), ldlt_.vectorD(), p_, pinv_, b);
}

}  // namespace c4d
