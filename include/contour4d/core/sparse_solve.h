#pragma once
//! \file sparse_solve.h
//! \brief A sparse LDLᵀ factorisation (SimplicialLDLT's, bit for bit, factored faster) solved for several
//! right-hand sides in one pass. Plain data in and out: Eigen stays inside the library's .cpp files.

#include <memory>
#include <utility>

namespace c4d {

//! The lower triangle of a square symmetric matrix in compressed-column form (Eigen's compressed
//! SparseMatrix storage): column j holds rows inner[outer[j] .. outer[j + 1]) with values value[...].
struct SparseLowerView {
  int n = 0;                      //!< rows = columns
  const int* outer = nullptr;     //!< n + 1 column starts
  const int* inner = nullptr;     //!< row of each entry
  const double* value = nullptr;  //!< value of each entry
};

//! The factorisation of `Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>` (the lower triangle, AMD
//! ordering), bit for bit, with a cheaper ordering step and a faster numeric factorisation.
//!
//! Eigen's ordering step copies the matrix into full symmetric storage, then adds that copy's transpose
//! to it (AMDOrdering's A + Aᵀ), only to hand the pattern to its minimum-degree routine. Here the full
//! symmetric pattern is written straight from the lower triangle, and Eigen's own minimum-degree routine
//! and permutation follow. The symbolic analysis and numeric factorisation are Eigen's algorithm (Davis's
//! up-looking LDLᵀ) with the same operations in the same order for every value, but the updates from a
//! chain of columns with nested rows (a supernode) to the rows below it are made row by row on contiguous
//! values, several rows per SIMD instruction: the factor, and solve()'s result, are SimplicialLDLT's (tested).
//! Solving reads each column of the factor once for all right-hand sides (Eigen's solve streams the whole
//! factor once per right-hand side), with Eigen 3.4's operations in Eigen's order for each.
class SparseLdlt {
 public:
  struct Factor;  //!< the factor (src/core/sparse_solve_internal.h)

  //! `lanes`: rows per SIMD step: 0 the widest the CPU runs, 1, 2 or 4; the result is the same bit for bit
  //! (tested), the time not.
  explicit SparseLdlt(int lanes = 0);
  ~SparseLdlt();
  SparseLdlt(SparseLdlt&&) noexcept;
  SparseLdlt& operator=(SparseLdlt&&) noexcept;

  //! Factors the symmetric matrix whose lower triangle `a` holds (entries above the diagonal are not read).
  //! False when the factorisation fails (a zero pivot).
  bool compute(const SparseLowerView& a);
  //! x = A⁻¹ b for `columns` right-hand sides of size() values each, stored column after column.
  //! \pre compute() succeeded.
  void solve(const double* b, double* x, int columns) const;
  //! The matrix size (0 before compute()).
  int size() const;
  //! The smallest and largest entry of the factor's diagonal D (a tiny one: a nearly singular system).
  std::pair<double, double> pivot_range() const;
  //! The factor itself, for white-box tests.
  const Factor& factor() const { return *factor_; }

 private:
  std::unique_ptr<Factor> factor_;
  int lanes_ = 0;
};

//! Factors an Eigen-like sparse matrix `a` (its lower triangle; compressed or not) into `s`.
template <class SparseMatrix>
bool factor_lower(SparseLdlt& s, const SparseMatrix& a) {
  if (!a.isCompressed()) {
    SparseMatrix c = a;
    c.makeCompressed();
    return factor_lower(s, c);
  }
  return s.compute({static_cast<int>(a.rows()), a.outerIndexPtr(), a.innerIndexPtr(), a.valuePtr()});
}

//! s's solution for every column of an Eigen-like dense column-major matrix `b`.
template <class Dense>
Dense ldlt_solve(const SparseLdlt& s, const Dense& b) {
  Dense x(b.rows(), b.cols());
  s.solve(b.data(), x.data(), static_cast<int>(b.cols()));
  return x;
}

}  // namespace c4d
