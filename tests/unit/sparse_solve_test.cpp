// solve_ldlt (core/sparse_solve.h) against Eigen's own SimplicialLDLT::solve: bit-identical results.
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "contour4d/core/sparse_solve.h"

namespace c4d {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

// I + w LᵀL for the umbrella Laplacian L of a g × g grid with random edge weights: symmetric positive
// definite, with the bi-Laplacian's fill, as the 4D morph's projection system.
Sparse grid_system(int g, double w, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.5, 2.0);
  const int n = g * g;
  std::vector<Eigen::Triplet<double>> t;
  for (int r = 0; r < g; ++r)
    for (int c = 0; c < g; ++c) {
      const int i = r * g + c;
      std::vector<std::pair<int, double>> nb;
      if (r > 0) nb.push_back({i - g, u(rng)});
      if (r + 1 < g) nb.push_back({i + g, u(rng)});
      if (c > 0) nb.push_back({i - 1, u(rng)});
      if (c + 1 < g) nb.push_back({i + 1, u(rng)});
      double sum = 0;
      for (const auto& [j, x] : nb) sum += x;
      t.emplace_back(i, i, 1.0);
      for (const auto& [j, x] : nb) t.emplace_back(i, j, -x / sum);
    }
  Sparse L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  Sparse I(n, n);
  I.setIdentity();
  return Sparse(I + w * Sparse(L.transpose() * L));
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(SparseSolve, EqualsEigensSolveBitForBit) {
  std::mt19937 rng(7);
  std::normal_distribution<double> nd(0.0, 10.0);
  const Sparse A = grid_system(40, 1.0, rng);
  Eigen::SimplicialLDLT<Sparse> solver(A);
  ASSERT_EQ(solver.info(), Eigen::Success);
  for (int cols : {1, 2, 3, 5}) {
    Eigen::MatrixXd b(A.rows(), cols);
    for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = nd(rng);
    // Zeros (also negative zeros) in some rows and columns: Eigen skips them in the forward solve.
    for (Eigen::Index i = 0; i < b.rows(); i += 7) b(i, 0) = 0.0;
    for (Eigen::Index i = 3; i < b.rows(); i += 11) b(i, cols - 1) = -0.0;
    const Eigen::MatrixXd ours = solve_ldlt(solver, b), eigen = solver.solve(b);
    EXPECT_TRUE(same_bits(ours, eigen)) << cols << " columns";
    EXPECT_LT((A * ours - b).norm(), 1e-8 * b.norm());
  }
}

TEST(SparseSolve, HandlesTheIdentityAndAnEmptyRightHandSide) {
  Sparse I(5, 5);
  I.setIdentity();
  Eigen::SimplicialLDLT<Sparse> solver(I);
  ASSERT_EQ(solver.info(), Eigen::Success);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(5, 3);
  EXPECT_TRUE(same_bits(solve_ldlt(solver, b), solver.solve(b)));
  EXPECT_EQ(solve_ldlt(solver, Eigen::MatrixXd(5, 0)).cols(), 0);
}

}  // namespace
}  // namespace c4d
