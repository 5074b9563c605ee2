#include "Common/GraphSeparator.h"
#include "Common/SparseCholesky.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <random>
#include <vector>

using otparam::Adjacency;
using otparam::SparseCholesky;
using SparseMatrix = SparseCholesky::SparseMatrix;

namespace
{
// The graph Laplacian of a k x k grid with its first corner pinned (positive definite), in the
// order "interior points, then the border": the conformal map's Neumann Laplacian, whose
// leading block is the Dirichlet one. Lower triangle only. `bottomRowOnly`: the border is the
// bottom row only (a short trailing block).
SparseMatrix borderedGrid(int k, int& interior, bool bottomRowOnly = false)
{
  const int n = k * k;
  std::vector<int> id(n);
  int next = 0;
  auto onBorder = [k, bottomRowOnly](int i, int j)
  { return j == 0 || (!bottomRowOnly && (i == 0 || i == k - 1 || j == k - 1)); };
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

void checkLeadingBlock(int k, bool bottomRowOnly = false, bool inHalves = false)
{
  int interior = 0;
  const SparseMatrix lower = borderedGrid(k, interior, bottomRowOnly);
  const int n = static_cast<int>(lower.rows());
  SparseCholesky both;
  both.allowHalves(true);
  ASSERT_TRUE(both.computeWithLeadingBlock(lower, interior));
  EXPECT_EQ(both.factoredInHalves(), inHalves);
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
  // CHOLMOD from CholmodThreshold unknowns; the whole border (1836 unknowns) trailing makes
  // the halves' dense Schur complement too dear, so this is one factorization.
  checkLeadingBlock(460);
}

// A short trailing block (the bottom row, 459 unknowns after the pinned corner): the leading
// block is split in two halves by a level of the grid, and the halves' factors still solve the
// matrix, its leading block and give its trailing Schur complement.
TEST(SparseCholesky, TwoHalvesSolveTheMatrixAndItsLeadingBlock)
{
  checkLeadingBlock(460, true, true);
}

// The halves side by side on two threads or in turn on one: the same bits.
TEST(SparseCholesky, TwoHalvesGiveTheSameBitsOnOneAndTwoThreads)
{
  int interior = 0;
  const SparseMatrix lower = borderedGrid(460, interior);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(lower.rows(), 2);
  std::vector<Eigen::MatrixXd> solutions;
  for (int threads : { 1, 2 })
  {
    omp_set_num_threads(threads);
    SparseCholesky cholesky;
    cholesky.allowHalves(true);
    ASSERT_TRUE(cholesky.compute(lower));
    ASSERT_TRUE(cholesky.factoredInHalves());
    solutions.push_back(cholesky.solve(b));
    EXPECT_LT(relativeResidual(lower, solutions.back(), b), 1e-10);
  }
  omp_set_num_threads(2);
  EXPECT_EQ((solutions[0] - solutions[1]).cwiseAbs().maxCoeff(), 0.0);
}

// A grid's level structure: two sides that no edge joins, each at least an eighth of the
// vertices, the separator one anti-diagonal; a second component joins the smaller side.
TEST(GraphSeparator, LevelOfAGridSeparatesTwoSides)
{
  const int k = 40, n = k * k;
  auto build = [&](int copies)
  {
    Adjacency graph;
    graph.offsets.push_back(0);
    for (int c = 0; c < copies; ++c)
    {
      for (int v = 0; v < n; ++v)
      {
        const int i = v % k, j = v / k;
        for (auto [di, dj] : { std::pair{ -1, 0 }, { 1, 0 }, { 0, -1 }, { 0, 1 } })
        {
          if (i + di >= 0 && i + di < k && j + dj >= 0 && j + dj < k)
          {
            graph.targets.push_back(c * n + (j + dj) * k + i + di);
          }
        }
        graph.offsets.push_back(static_cast<int>(graph.targets.size()));
      }
    }
    return graph;
  };
  for (int copies : { 1, 2 })
  {
    const Adjacency graph = build(copies);
    std::vector<otparam::SeparatorPart> part;
    std::int64_t sizes[3] = { 0, 0, 0 };
    const double cost = otparam::separateByLevels(
      graph,
      [&](std::int64_t first, std::int64_t second, std::int64_t separator)
      { return double(std::max(first, second)) + 10.0 * separator; },
      part);
    ASSERT_TRUE(std::isfinite(cost));
    ASSERT_EQ(part.size(), static_cast<size_t>(graph.size()));
    for (int v = 0; v < graph.size(); ++v)
    {
      ++sizes[static_cast<int>(part[v])];
      for (int e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
      {
        const auto a = part[v], b = part[graph.targets[e]];
        EXPECT_FALSE(a != b && a != otparam::SeparatorPart::Separator &&
          b != otparam::SeparatorPart::Separator)
          << "edge " << v << "-" << graph.targets[e] << " joins the two sides";
      }
    }
    EXPECT_GE(8 * std::min(sizes[0], sizes[1]), graph.size());
    EXPECT_LE(sizes[2], k); // an anti-diagonal from a corner, at most k long
    EXPECT_EQ(cost, double(std::max(sizes[0], sizes[1])) + 10.0 * sizes[2]);
  }
  Adjacency path; // too small to split
  path.offsets = { 0, 1, 2 };
  path.targets = { 1, 0 };
  std::vector<otparam::SeparatorPart> part;
  EXPECT_FALSE(std::isfinite(otparam::separateByLevels(
    path, [](std::int64_t, std::int64_t, std::int64_t) { return 0.0; }, part)));
  EXPECT_TRUE(part.empty());
}
