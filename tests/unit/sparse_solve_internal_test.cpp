// solve_ldlt and SparseLdlt (core/sparse_solve.h, white-box: its factor in core/sparse_solve_internal.h)
// against Eigen's own SimplicialLDLT: bit-identical factors and results.
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "contour4d/core/sparse_solve.h"
#include "core/sparse_solve_internal.h"

namespace c4d {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using detail::solve_ldlt;

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

bool same_bits(const Sparse& a, const Sparse& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
    Sparse::InnerIterator x(a, j), y(b, j);
    for (; x && y; ++x, ++y)
      if (x.row() != y.row() || std::memcmp(&x.valueRef(), &y.valueRef(), sizeof(double)) != 0) return false;
    if (x || y) return false;
  }
  return true;
}

// SparseLdlt orders from the lower triangle's pattern itself and factors with its own loops: the same
// permutation, factor and solutions as SimplicialLDLT on grids of several sizes and weights (the
// fairing's and the morph's systems; their supernodes take the chain updates), at every SIMD width, also
// when the upper triangle holds other values (it is never read) or is not stored.
TEST(SparseSolve, SparseLdltIsSimplicialLdltBitForBit) {
  std::mt19937 rng(3);
  std::normal_distribution<double> nd(0.0, 10.0);
  for (const auto& [g, w] : {std::pair{7, 1.0}, std::pair{30, 0.01}, std::pair{45, 100.0}}) {
    const Sparse A = grid_system(g, w, rng);
    Sparse lower = A.triangularView<Eigen::Lower>();
    Sparse skewed = A;  // the upper triangle scaled: neither solver reads it
    for (Eigen::Index j = 0; j < skewed.outerSize(); ++j)
      for (Sparse::InnerIterator it(skewed, j); it; ++it)
        if (it.row() < j) it.valueRef() *= 3.0;
    const Eigen::SimplicialLDLT<Sparse> eigen(A);
    ASSERT_EQ(eigen.info(), Eigen::Success);
    Eigen::MatrixXd b(A.rows(), 3);
    for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = nd(rng);
    for (const Sparse* input : std::vector<const Sparse*>{&A, &lower, &skewed})
      for (int lanes : {0, 1, 2, 4}) {  // the chains' updates at every SIMD width, and Eigen's loop alone
        SparseLdlt ours(lanes);
        ASSERT_TRUE(factor_lower(ours, *input));
        EXPECT_TRUE(same_bits(Eigen::MatrixXd(ours.factor().d), Eigen::MatrixXd(eigen.vectorD()))) << g << " " << lanes;
        EXPECT_TRUE(same_bits(ldlt_solve(ours, b), eigen.solve(b))) << g << " " << lanes;
        EXPECT_TRUE(same_bits(ours.factor().l, Sparse(eigen.matrixL().nestedExpression()))) << g << " " << lanes;
      }
    // The factor itself: SimplicialLDLT with the natural ordering on the permuted matrix (what SparseLdlt
    // runs) has the factor of SimplicialLDLT with AMD.
    Sparse ap(A.rows(), A.cols());
    ap.selfadjointView<Eigen::Upper>() = A.selfadjointView<Eigen::Lower>().twistedBy(eigen.permutationP());
    const Eigen::SimplicialLDLT<Sparse, Eigen::Upper, Eigen::NaturalOrdering<int>> natural(ap);
    EXPECT_TRUE(same_bits(Sparse(natural.matrixL()), Sparse(eigen.matrixL()))) << g;
  }
  // A singular matrix (a zero pivot) fails in both.
  Sparse bad(2, 2);
  bad.insert(0, 0) = 1.0;
  bad.insert(1, 0) = 2.0;
  bad.insert(0, 1) = 2.0;
  bad.insert(1, 1) = 4.0;
  SparseLdlt ours;
  const Eigen::SimplicialLDLT<Sparse> eigen(bad);
  EXPECT_EQ(factor_lower(ours, bad), eigen.info() == Eigen::Success);
}

}  // namespace
}  // namespace c4d
