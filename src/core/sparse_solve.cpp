// A multi-right-hand-side solve with Eigen's SimplicialLDLT factor (Eigen 3.4, SimplicialCholesky.h
// _solve_impl and SparseCore/TriangularSolver.h), for the linear systems of the surface fairing, the 4D
// morph's projection and the contour fit.
#include "contour4d/core/sparse_solve.h"
#include "sparse_solve_internal.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "contour4d/core/cpu.h"
#include "simd/ldlt_internal.h"

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

// x = P⁻¹ L⁻ᵀ D⁻¹ L⁻¹ P b (SimplicialLDLT::_solve_impl's order; P empty: none). Three right-hand sides
// take the AVX path where the CPU has it, unless lanes is 1 or 2 (SparseLdlt's lanes, for the tests).
template <class Perm>
Eigen::MatrixXd permuted_solve(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& d, const Perm& P,
                               const Perm& Pinv, const Eigen::MatrixXd& b, int lanes = 0) {
  using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Index n = b.rows(), nc = b.cols();
  static const bool avx = detail::avx_available();
  const bool four_wide = nc == 3 && avx && lanes != 1 && lanes != 2;
  // The columns side by side, one row per unknown; on the AVX path a fourth, zero column makes each row
  // one four-wide load.
  Rows y = Rows::Zero(n, four_wide ? 4 : nc);
  if (P.size() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) y.row(P.indices()(i)).head(nc) = b.row(i);
  } else {
    y.leftCols(nc) = b;
  }
  if (four_wide)
    detail::ldlt_substitute3_avx(L.outerIndexPtr(), L.innerNonZeroPtr(), L.innerIndexPtr(), L.valuePtr(), L.nonZeros(),
                                 d.size() > 0 ? d.data() : nullptr, n, y.data());
  else if (nc == 3)
    substitute<3>(L, d, y.data(), n, nc);
  else
    substitute<0>(L, d, y.data(), n, nc);
  Eigen::MatrixXd x(n, nc);
  if (P.size() > 0) {
    for (Eigen::Index i = 0; i < n; ++i) x.row(Pinv.indices()(i)) = y.row(i).head(nc);
  } else {
    x = y.leftCols(nc);
  }
  return x;
}

}  // namespace

Eigen::MatrixXd detail::solve_ldlt(const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& solver,
                                   const Eigen::MatrixXd& b) {
  return permuted_solve(solver.matrixL().nestedExpression(), solver.vectorD(), solver.permutationP(),
                        solver.permutationPinv(), b);
}

namespace {

// y[rows[q]] −= columns[t][q] · yv[t] for every q < below, t = 0, 1, ..., run − 1 in that order (a
// multiplication, then a subtraction): four rows per AVX instruction where the CPU has it, else two per SSE2
// instruction (simd/ldlt_internal.h), each lane a row's own chain of operations.
void rows_below(double* y, const int* rows, int below, const double* const* columns, const double* yv, int run,
                int lanes) {
  static const bool avx = detail::avx_available();
  if (avx && lanes != 2) {
    detail::ldlt_rows_below_avx(y, rows, below, columns, yv, run);
    return;
  }
  int q = detail::ldlt_rows_below_sse2(y, rows, below, columns, yv, run);
  for (; q < below; ++q) {
    double a = y[rows[q]];
    for (int t = 0; t < run; ++t) a -= columns[t][q] * yv[t];
    y[rows[q]] = a;
  }
}

// Davis's up-looking LDLᵀ (T. A. Davis, "Algorithm 849: a concise sparse Cholesky factorization
// package", ACM TOMS 31(4), 2005), as Eigen 3.4's SimplicialLDLT runs it (SimplicialCholesky_impl.h:
// analyzePattern_preordered and factorize_preordered<true>), on the upper triangle `ap` (column k: rows
// i <= k) of an already ordered matrix. The factor (strictly lower, columns in row order), D and the
// outcome are Eigen's to the bit: every value gets the same operations in the same order. What differs
// is where the time goes.
//
// Row k of L is a sparse triangular solve: each column i in row k's pattern (in the topological order
// the elimination tree gives) subtracts L(j, i)·y_i from y_j for every row j < k of column i, through
// an index per entry. Where the pattern lists i, i + 1, ..., i1 in a row and each column's rows are
// those of the next plus that next column itself (a chain of the elimination tree with nested columns:
// a supernode), the rows below the chain are the same for all its columns. The columns' updates of
// those rows are then made after the chain, row by row, each row's updates in the chain's order, on
// contiguous values and several rows per SIMD instruction (rows_below; IEEE subtraction and
// multiplication are correctly rounded packed or not; no fused multiply-add). Nothing between reads
// those rows: they are the chain's ancestors, later in the pattern. The chain's own rows (the dense
// triangle of a supernode, most of the work at the top of the tree) are taken in blocks of rows the same
// way: each block first gets the updates of the chain's columns before it, then its own columns'. Flops
// stay the same; the index traffic and the scattered read-modify-writes of y go (the fairing's factorisation
// takes well under half of Eigen's loop's time).
struct UpLooking {
  std::vector<int> parent, count;  // elimination tree; non-zeros per column of L (below the diagonal)
  std::vector<char> chain;         // column i's rows are {i + 1} and those of column i + 1

  void analyze(const Eigen::SparseMatrix<double>& ap) {
    const auto n = static_cast<int>(ap.cols());
    parent.assign(static_cast<std::size_t>(n), -1);
    count.assign(static_cast<std::size_t>(n), 0);
    std::vector<int> tags(static_cast<std::size_t>(n), 0);
    for (int k = 0; k < n; ++k) {
      tags[static_cast<std::size_t>(k)] = k;
      for (Eigen::SparseMatrix<double>::InnerIterator it(ap, k); it; ++it) {
        auto i = static_cast<int>(it.index());
        if (i >= k) continue;
        for (; tags[static_cast<std::size_t>(i)] != k; i = parent[static_cast<std::size_t>(i)]) {
          if (parent[static_cast<std::size_t>(i)] == -1) parent[static_cast<std::size_t>(i)] = k;
          ++count[static_cast<std::size_t>(i)];
          tags[static_cast<std::size_t>(i)] = k;
        }
      }
    }
    chain.assign(static_cast<std::size_t>(n), 0);
    for (int i = 0; i + 1 < n; ++i)
      chain[static_cast<std::size_t>(i)] =
          parent[static_cast<std::size_t>(i)] == i + 1 &&
          count[static_cast<std::size_t>(i)] == count[static_cast<std::size_t>(i) + 1] + 1;
  }

  // Numeric factorisation into l (strictly lower, compressed) and d; false at a zero pivot (as Eigen,
  // which stops there).
  // lanes: SparseLdlt's; 1 runs Eigen's loop for every column.
  bool factorize(const Eigen::SparseMatrix<double>& ap, Eigen::SparseMatrix<double>& l, Eigen::VectorXd& d,
                 int lanes) const {
    const auto n = static_cast<int>(ap.cols());
    l.resize(n, n);
    int* lp = l.outerIndexPtr();
    lp[0] = 0;
    for (int k = 0; k < n; ++k) lp[k + 1] = lp[k] + count[static_cast<std::size_t>(k)];
    l.resizeNonZeros(lp[n]);
    int* li = l.innerIndexPtr();
    double* lx = l.valuePtr();
    d.resize(n);
    double* dk = d.data();
    std::vector<double> y(static_cast<std::size_t>(n), 0.0), yv;
    std::vector<int> pattern(static_cast<std::size_t>(n)), tags(static_cast<std::size_t>(n), 0),
        nz(static_cast<std::size_t>(n), 0);
    std::vector<const double*> columns, inner;
    constexpr int kBlock = 16;
    std::vector<int> block_rows(static_cast<std::size_t>(kBlock));
    for (int k = 0; k < n; ++k) {
      // Row k's pattern, in topological order.
      y[static_cast<std::size_t>(k)] = 0.0;
      int top = n;
      tags[static_cast<std::size_t>(k)] = k;
      nz[static_cast<std::size_t>(k)] = 0;
      for (Eigen::SparseMatrix<double>::InnerIterator it(ap, k); it; ++it) {
        auto i = static_cast<int>(it.index());
        if (i > k) continue;
        y[static_cast<std::size_t>(i)] += it.value();
        int len = 0;
        for (; tags[static_cast<std::size_t>(i)] != k; i = parent[static_cast<std::size_t>(i)]) {
          pattern[static_cast<std::size_t>(len++)] = i;
          tags[static_cast<std::size_t>(i)] = k;
        }
        while (len > 0) pattern[static_cast<std::size_t>(--top)] = pattern[static_cast<std::size_t>(--len)];
      }
      double diag = y[static_cast<std::size_t>(k)] * 1.0 + 0.0;  // Eigen's shift: scale 1, offset 0
      y[static_cast<std::size_t>(k)] = 0.0;
      while (top < n) {
        // The chain starting here: i0, i0 + 1, ..., i1 listed one after the other.
        int end = top + 1;
        while (end < n && chain[static_cast<std::size_t>(pattern[static_cast<std::size_t>(end) - 1])] &&
               pattern[static_cast<std::size_t>(end)] == pattern[static_cast<std::size_t>(end) - 1] + 1)
          ++end;
        const int i1 = pattern[static_cast<std::size_t>(end) - 1];
        const int below = nz[static_cast<std::size_t>(i1)];  // rows < k below the chain (column i1's so far)
        const int run = end - top;
        if (run == 1 || lanes == 1) {  // Eigen's loop as it is
          for (; top < end; ++top) {
            const int i = pattern[static_cast<std::size_t>(top)];
            const double yi = y[static_cast<std::size_t>(i)];
            y[static_cast<std::size_t>(i)] = 0.0;
            const double lki = yi / dk[i];
            const int p2 = lp[i] + nz[static_cast<std::size_t>(i)];
            for (int p = lp[i]; p < p2; ++p) y[static_cast<std::size_t>(li[p])] -= lx[p] * yi;
            diag -= lki * yi;
            li[p2] = k;
            lx[p2] = lki;
            ++nz[static_cast<std::size_t>(i)];
          }
          continue;
        }
        // The chain's own rows (column i's first i1 − i entries: rows i + 1..i1), in blocks of kBlock rows:
        // first each block's updates from the chain's columns before it (done: their y_i are final), row by
        // row as below the chain, then the block's own columns one by one, as Eigen updates them. Each
        // row still gets its updates in the chain's order.
        yv.resize(static_cast<std::size_t>(run));
        columns.resize(static_cast<std::size_t>(run));
        inner.resize(static_cast<std::size_t>(run));
        const int i0 = pattern[static_cast<std::size_t>(top)];
        for (int b0 = 0; b0 < run; b0 += kBlock) {
          const int b1 = std::min(run, b0 + kBlock);
          if (b0 > 0) {
            for (int t = 0; t < b0; ++t) inner[static_cast<std::size_t>(t)] = lx + lp[i0 + t] + (b0 - t - 1);
            for (int r = b0; r < b1; ++r) block_rows[static_cast<std::size_t>(r - b0)] = i0 + r;
            rows_below(y.data(), block_rows.data(), b1 - b0, inner.data(), yv.data(), b0, lanes);
          }
          for (int t = b0; t < b1; ++t) {
            const int i = i0 + t;
            const double yi = y[static_cast<std::size_t>(i)];
            y[static_cast<std::size_t>(i)] = 0.0;
            const double lki = yi / dk[i];
            const int inside = i1 - i;
            const int base = lp[i];
            for (int q = 0; q < b1 - 1 - t; ++q)
              y[static_cast<std::size_t>(i) + 1 + static_cast<std::size_t>(q)] -= lx[base + q] * yi;
            diag -= lki * yi;
            const int p2 = base + nz[static_cast<std::size_t>(i)];
            li[p2] = k;
            lx[p2] = lki;
            ++nz[static_cast<std::size_t>(i)];
            yv[static_cast<std::size_t>(t)] = yi;
            columns[static_cast<std::size_t>(t)] = lx + base + inside;  // its rows below the chain
          }
        }
        top = end;
        // The rows below the chain, each with the chain's updates in the chain's order.
        rows_below(y.data(), li + lp[i1], below, columns.data(), yv.data(), run, lanes);
      }
      dk[k] = diag;
      if (diag == 0.0) return false;
    }
    return true;
  }
};

}  // namespace

SparseLdlt::SparseLdlt(int lanes) : factor_(std::make_unique<Factor>()), lanes_(lanes) {}
SparseLdlt::~SparseLdlt() = default;
SparseLdlt::SparseLdlt(SparseLdlt&&) noexcept = default;
SparseLdlt& SparseLdlt::operator=(SparseLdlt&&) noexcept = default;

int SparseLdlt::size() const { return static_cast<int>(factor_->d.size()); }

std::pair<double, double> SparseLdlt::pivot_range() const {
  const Eigen::VectorXd& d = factor_->d;
  if (d.size() == 0) return {0.0, 0.0};
  return {d.minCoeff(), d.maxCoeff()};
}

bool SparseLdlt::compute(const SparseLowerView& view) {
  using Sparse = Eigen::SparseMatrix<double>;
  const Eigen::Map<const Sparse> a(view.n, view.n, view.n > 0 ? view.outer[view.n] : 0, view.outer, view.inner,
                                   view.value);
  const Eigen::Index n = a.cols();
  auto& p_ = factor_->p;
  auto& pinv_ = factor_->pinv;
  // The full symmetric pattern of the lower triangle, each column sorted: column j gets the rows k < j
  // of the earlier columns that hold (j, k) (in increasing k), then its own entries i >= j (increasing).
  // Eigen's ordering step builds the same pattern as C + Cᵀ, C the full symmetric copy.
  std::vector<int> count(static_cast<std::size_t>(n) + 1, 0);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Map<const Sparse>::InnerIterator it(a, j); it; ++it)
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
      for (Eigen::Map<const Sparse>::InnerIterator it(a, j); it; ++it) {
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
  UpLooking factor;
  factor.analyze(ap);
  factor_->ok = factor.factorize(ap, factor_->l, factor_->d, lanes_);
  return factor_->ok;
}

void SparseLdlt::solve(const double* b, double* x, int columns) const {
  const Eigen::Index n = factor_->d.size();
  const Eigen::Map<const Eigen::MatrixXd> rhs(b, n, columns);
  Eigen::Map<Eigen::MatrixXd>(x, n, columns) =
      permuted_solve(factor_->l, factor_->d, factor_->p, factor_->pinv, Eigen::MatrixXd(rhs), lanes_);
}

}  // namespace c4d
