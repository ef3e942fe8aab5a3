#pragma once
//! \file sparse_solve.h
//! \brief Solves with a sparse LDLᵀ factorisation (Eigen) for several right-hand sides in one pass.

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>

namespace c4d {

//! `solver.solve(b)`, bit for bit, for all of b's columns (x, y and z of a mesh) at once.
//!
//! Eigen's sparse triangular solves go column by column, and each column streams the whole factor from
//! memory (the 4D morph's factor on the left heart: 3 million non-zeros, 36 MB): here each column of
//! the factor is read once for every right-hand side. Each right-hand side gets Eigen 3.4's operations
//! in Eigen's order (SimplicialLDLT::_solve_impl), so the result equals `solver.solve(b)` exactly
//! (tested). `solver` must hold a successful factorisation.
Eigen::MatrixXd solve_ldlt(const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& solver, const Eigen::MatrixXd& b);

//! The factorisation of `Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>` (the lower triangle, AMD
//! ordering), bit for bit, with a cheaper ordering step and a faster numeric factorisation.
//!
//! Eigen's ordering step copies the matrix into full symmetric storage, then adds that copy's transpose
//! to it (AMDOrdering's A + Aᵀ), only to hand the pattern to its minimum-degree routine: on the left
//! heart's fairing those copies took 7 of the step's 16 ms. Here the full symmetric pattern is written
//! straight from the lower triangle (each column sorted, as Eigen's sum leaves it), and Eigen's own
//! minimum-degree routine and permutation follow. The symbolic analysis and numeric factorisation are
//! Eigen's algorithm (Davis's up-looking LDLᵀ) with the same operations in the same order for every
//! value, but the updates from a chain of columns with nested rows (a supernode) to the rows below it
//! are made row by row on contiguous values, two rows per SSE2 instruction, instead of through an index
//! per entry: the factor, and solve()'s result, are those of SimplicialLDLT (tested).
class SparseLdlt {
 public:
  //! `lanes`: rows per SIMD step of the factorisation's chain updates: 0 the widest the CPU runs (4 with
  //! AVX, else 2), 2, 4 (without AVX: 2) or 1 (Eigen's loop throughout); the factor is the same bit for
  //! bit (tested), the time not. With AVX, solve() updates three right-hand sides per instruction
  //! unless lanes is 1 or 2 (the same result).
  explicit SparseLdlt(int lanes = 0) : lanes_(lanes) {}
  //! Factors the symmetric matrix whose lower triangle `a` holds (square, column-major; the upper
  //! triangle is not read). False when the factorisation fails (info() says why).
  bool compute(const Eigen::SparseMatrix<double>& a);
  //! SimplicialLDLT::solve(b) for every column of b, as solve_ldlt. \pre compute() succeeded.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;
  //! The diagonal D of the factor (in the permuted order).
  const Eigen::VectorXd& vectorD() const { return d_; }
  //! The factor's unit lower triangle L, without its diagonal (SimplicialLDLT's matrixL() storage).
  const Eigen::SparseMatrix<double>& matrixL() const { return l_; }
  Eigen::ComputationInfo info() const { return ok_ ? Eigen::Success : Eigen::NumericalIssue; }

 private:
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p_, pinv_;
  Eigen::SparseMatrix<double> l_;
  Eigen::VectorXd d_;
  bool ok_ = false;
  int lanes_ = 0;
};

}  // namespace c4d
