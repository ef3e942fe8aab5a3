#pragma once
// SparseLdlt's factor (sparse_solve.h) in Eigen's types, and the fast solve for Eigen's own SimplicialLDLT:
// for sparse_solve.cpp and its white-box test (tests/unit/sparse_solve_internal_test.cpp).

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>

#include "contour4d/core/sparse_solve.h"

namespace c4d {

struct SparseLdlt::Factor {
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p, pinv;  // the fill-reducing ordering
  Eigen::SparseMatrix<double> l;  // the unit lower triangle L without its diagonal (SimplicialLDLT's matrixL())
  Eigen::VectorXd d;              // the diagonal D (in the permuted order)
  bool ok = false;
};

namespace detail {

// `solver.solve(b)`, bit for bit, for all of b's columns at once (SparseLdlt's solve for Eigen's factor).
Eigen::MatrixXd solve_ldlt(const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& solver, const Eigen::MatrixXd& b);

}  // namespace detail
}  // namespace c4d
