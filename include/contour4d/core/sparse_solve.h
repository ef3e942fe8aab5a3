#pragma once
//! \file sparse_solve.h
//! \brief Solves with a sparse LDLᵀ factorisation (Eigen) for several right-hand sides in one pass.

#include <Eigen/Dense>
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

}  // namespace c4d
