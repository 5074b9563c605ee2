#include "Conformal/TutteEmbedding.h"

#include "Common/SparseCholesky.h"

#include <algorithm>
#include <set>
#include <utility>

namespace otparam
{

std::string tutteEmbedding(
  const std::vector<Triangle>& triangles, const std::vector<char>& fixed, std::vector<Vec2>& uv)
{
  std::set<std::pair<int, int>> edges;
  for (const Triangle& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      edges.insert({ std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]) });
    }
  }
  // The free points' rows of the graph Laplacian; fixed neighbours go to the right-hand side.
  std::vector<int> row(uv.size(), -1);
  int rows = 0;
  for (const auto& [a, b] : edges)
  {
    for (int v : { a, b })
    {
      if (!fixed[v] && row[v] < 0)
      {
        row[v] = rows++;
      }
    }
  }
  if (rows == 0)
  {
    return "";
  }
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> degree(rows, 0.0);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(rows, 2);
  bool anchored = false;
  for (const auto& [a, b] : edges)
  {
    for (const auto& [v, w] : { std::pair<int, int>{ a, b }, std::pair<int, int>{ b, a } })
    {
      if (row[v] < 0)
      {
        continue;
      }
      degree[row[v]] += 1.0;
      if (row[w] >= 0)
      {
        if (row[w] < row[v])
        {
          entries.emplace_back(row[v], row[w], -1.0);
        }
      }
      else
      {
        anchored = true;
        rhs(row[v], 0) += uv[w].x;
        rhs(row[v], 1) += uv[w].y;
      }
    }
  }
  if (!anchored)
  {
    return "the patch has no fixed point";
  }
  for (int r = 0; r < rows; ++r)
  {
    entries.emplace_back(r, r, degree[r]);
  }
  SparseCholesky::SparseMatrix lower(rows, rows);
  lower.setFromTriplets(entries.begin(), entries.end());
  SparseCholesky cholesky;
  if (!cholesky.compute(lower))
  {
    return "its Laplacian is singular (a part of the patch reaches no fixed point)";
  }
  const Eigen::MatrixXd x = cholesky.solve(rhs);
  for (size_t v = 0; v < uv.size(); ++v)
  {
    if (row[v] >= 0)
    {
      uv[v] = { x(row[v], 0), x(row[v], 1) };
    }
  }
  return "";
}

} // namespace otparam
