#include "Common/SparseCholesky.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using otparam::SparseCholesky;
using SparseMatrix = SparseCholesky::SparseMatrix;

namespace
{
// The graph Laplacian of a k x k grid with its first corner pinned (positive definite), in the
// order "interior points, then the border": the conformal map's Neumann Laplacian, whose
// leading block is the Dirichlet one. Lower triangle only.
SparseMatrix borderedGrid(int k, int& interior)
{
  const int n = k * k;
  std::vector<int> id(n);
  int next = 0;
  auto onBorder = [k](int i, int j) { return i == 0 || j == 0 || i == k - 1 || j == k - 1; };
  for (int pass = 0; pass < 2; ++pass)
  {
    for (int j = 0; j < k; ++j)
    {
      for (int i = 0; i < k; ++i)
      {
        if (onBorder(i, j) == (pass == 1) && !(i == 0 && j == 0))
        {
          id[j * k + i] = next++;
        }
      }
    }
    interior = pass == 0 ? next : interior;
  }
  std::vector<Eigen::Triplet<double>> entries;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  auto edge = [&](int a, int b)
  {
    const double w = weight(random);
    for (int v : { a, b })
    {
      if (v != 0)
      {
        entries.emplace_back(id[v], id[v], w);
      }
    }
    if (a != 0 && b != 0)
    {
      entries.emplace_back(std::max(id[a], id[b]), std::min(id[a], id[b]), -w);
    }
  };
  for (int j = 0; j < k; ++j)
  {
    for (int i = 0; i < k; ++i)
    {
      if (i + 1 < k)
      {
        edge(j * k + i, j * k + i + 1);
      }
      if (j + 1 < k)
      {
        edge(j * k + i, (j + 1) * k + i);
      }
    }
  }
  SparseMatrix lower(next, next);
  lower.setFromTriplets(entries.begin(), entries.end());
  return lower;
}

double relativeResidual(
  const SparseMatrix& lower, const Eigen::MatrixXd& x, const Eigen::MatrixXd& b)
{
  const Eigen::MatrixXd ax = lower.selfadjointView<Eigen::Lower>() * x;
  return (ax - b).norm() / b.norm();
}

void checkLeadingBlock(int k)
{
  int interior = 0;
  const SparseMatrix lower = borderedGrid(k, interior);
  const int n = static_cast<int>(lower.rows());
  SparseCholesky both;
  ASSERT_TRUE(both.computeWithLeadingBlock(lower, interior));
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 2);
  EXPECT_LT(relativeResidual(lower, both.solve(b), b), 1e-10);
  const SparseMatrix a11 = lower.topLeftCorner(interior, interior);
  const Eigen::MatrixXd b1 = b.topRows(interior);
  const Eigen::MatrixXd x1 = both.solveLeading(b1);
  EXPECT_LT(relativeResidual(a11, x1, b1), 1e-10);
  // The same solution as a factorization of the leading block alone.
  SparseCholesky alone;
  ASSERT_TRUE(alone.compute(a11));
  EXPECT_LT((alone.solve(b1) - x1).norm() / x1.norm(), 1e-10);
  // The Schur complement read off the factor: A22 y - A21 A11^-1 A12 y, and back.
  const SparseCholesky::SchurFactor schur = both.trailingSchurFactor();
  const int trailing = n - interior;
  ASSERT_EQ(schur.lower.rows(), trailing);
  const Eigen::VectorXd y = Eigen::VectorXd::Random(trailing);
  const SparseMatrix full = lower.selfadjointView<Eigen::Lower>();
  const SparseMatrix a21 = full.bottomLeftCorner(trailing, interior);
  const SparseMatrix a22 = full.bottomRightCorner(trailing, trailing);
  const Eigen::VectorXd expected =
    a22 * y - a21 * alone.solve(Eigen::MatrixXd(a21.transpose() * y));
  EXPECT_LT((schur.apply(y) - expected).norm() / expected.norm(), 1e-11);
  EXPECT_LT((schur.solve(expected) - y).norm() / y.norm(), 1e-9);
}
} // namespace

TEST(SparseCholesky, OneFactorizationSolvesTheMatrixAndItsLeadingBlock)
{
  checkLeadingBlock(60); // Eigen's simplicial LDL^T
}

TEST(SparseCholesky, OneSupernodalFactorizationSolvesTheMatrixAndItsLeadingBlock)
{
  static_assert(SparseCholesky::CholmodThreshold <= 460 * 460 - 1, "a CHOLMOD size");
  checkLeadingBlock(460); // CHOLMOD from CholmodThreshold unknowns
}
