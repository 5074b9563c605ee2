// The cotangent Laplacian of a triangulation given by its edge lengths, shared by the disk and
// the sphere conformal maps.
#ifndef OTPARAM_CONFORMAL_COTANGENTLAPLACIAN_H
#define OTPARAM_CONFORMAL_COTANGENTLAPLACIAN_H

#include "Mesh/IntrinsicDelaunay.h"

#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace otparam
{

// The n x n cotangent Laplacian (positive semi-definite: diagonal = sum of the half-cotangent
// weights, off-diagonal = minus the weight), both triangles, from the triangulation's edge
// lengths (the mesh's own, or those of its intrinsic Delaunay triangulation).
inline Eigen::SparseMatrix<double> cotangentLaplacian(
  const IntrinsicTriangulation& triangulation, int n)
{
  // The diagonal is summed here, in the order the triplets would have summed it (Eigen adds
  // duplicates in their order): half the triplets for the same bits (1.09M points: 26M -> 14M,
  // whose assembly was most of the Laplacian's time).
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(6 * triangulation.triangles.size() + static_cast<size_t>(n));
  std::vector<double> diagonal(static_cast<size_t>(n), 0.0);
  std::vector<char> touched(static_cast<size_t>(n), 0); // a point of some triangle
  for (size_t t = 0; t < triangulation.triangles.size(); ++t)
  {
    const Triangle& tri = triangulation.triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      const double half = halfCotangent(triangulation.lengths[t], k);
      const int a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
      entries.emplace_back(a, b, -half);
      entries.emplace_back(b, a, -half);
      diagonal[a] += half;
      diagonal[b] += half;
      touched[a] = touched[b] = 1;
    }
  }
  for (int v = 0; v < n; ++v)
  {
    if (touched[v])
    {
      entries.emplace_back(v, v, diagonal[v]);
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

// The edge weights a conformal map's Laplacian is built with.
enum class LaplacianWeights
{
  Mesh,              // the mesh's cotangent weights
  IntrinsicDelaunay, // those of its intrinsic Delaunay triangulation (none negative)
  Floored,           // the mesh's, none below PositiveWeightFloor times their mean
};

// Where both cotangent Laplacians fold, it is at a coarse sharp corner or a needle: a point of
// three triangles whose weight toward one neighbour is negative (the mesh's Laplacian puts it
// outside its star) and whose intrinsic Delaunay triangulation keeps two neighbours (that one
// puts it on the segment between them, its triangles degenerate). With every weight of the
// mesh's own triangles positive, a harmonic map with convex boundary values cannot fold them
// (Tutte). The floor is small, so that elsewhere the weights are the mesh's.
constexpr double PositiveWeightFloor = 1e-2;

inline Eigen::SparseMatrix<double> withFlooredWeights(const Eigen::SparseMatrix<double>& L)
{
  double sum = 0.0;
  long long count = 0;
  for (int j = 0; j < L.outerSize(); ++j)
  {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
    {
      if (it.row() != it.col())
      {
        sum += std::abs(it.value());
        ++count;
      }
    }
  }
  const double floor = count > 0 ? PositiveWeightFloor * sum / static_cast<double>(count) : 0.0;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(L.nonZeros()));
  for (int j = 0; j < L.outerSize(); ++j)
  {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
    {
      if (it.row() != it.col())
      {
        const double weight = std::max(-it.value(), floor);
        const int row = static_cast<int>(it.row()), col = static_cast<int>(it.col());
        entries.emplace_back(row, col, -weight);
        entries.emplace_back(col, col, weight);
      }
    }
  }
  Eigen::SparseMatrix<double> floored(L.rows(), L.cols());
  floored.setFromTriplets(entries.begin(), entries.end());
  return floored;
}

// The Laplacian of a mesh's triangles with the given weights (`triangles` and `lengths` as for
// intrinsicDelaunay); `flips` gets the intrinsic Delaunay triangulation's edge flips.
inline Eigen::SparseMatrix<double> laplacianOf(const std::vector<Triangle>& triangles,
  const std::vector<std::array<double, 3>>& lengths, int n, LaplacianWeights weights, int& flips)
{
  const IntrinsicTriangulation triangulation = weights == LaplacianWeights::IntrinsicDelaunay
    ? intrinsicDelaunay(triangles, lengths)
    : IntrinsicTriangulation{ triangles, lengths, 0 };
  flips = triangulation.flips;
  const Eigen::SparseMatrix<double> L = cotangentLaplacian(triangulation, n);
  return weights == LaplacianWeights::Floored ? withFlooredWeights(L) : L;
}

// The fallbacks of both conformal maps where the mesh's own Laplacian folds triangles (`folded`
// of them): the intrinsic Delaunay Laplacian, kept when it folds fewer, then the floored
// weights, kept only where they fold none: a crowded surface's folds are not theirs to mend (a
// closed finger 54 radii long: they fold fewer triangles than the intrinsic Laplacian but leave
// a start its stages map worse, mean |log area ratio| 0.034 -> 0.047). `solve(weights)` maps
// again; `foldsOf(map)` counts its folded triangles, -1 if it failed; `adopt(map, weights)` keeps
// it, `discard(map)` drops it. An aborted solve is adopted, and ends the fallbacks.
template <class Solve, class FoldsOf, class Adopt, class Discard>
void tryFallbackLaplacians(std::int64_t folded, const Solve& solve, const FoldsOf& foldsOf,
  const Adopt& adopt, const Discard& discard)
{
  for (const LaplacianWeights fallback :
    { LaplacianWeights::IntrinsicDelaunay, LaplacianWeights::Floored })
  {
    if (folded == 0)
    {
      return;
    }
    auto other = solve(fallback);
    const bool aborted = other.status.aborted;
    const std::int64_t otherFolded = aborted ? -1 : foldsOf(other);
    const bool better = fallback == LaplacianWeights::Floored
      ? otherFolded == 0
      : 0 <= otherFolded && otherFolded < folded;
    if (!aborted && !better)
    {
      discard(other);
      continue;
    }
    adopt(std::move(other), fallback);
    folded = otherFolded;
    if (aborted)
    {
      return;
    }
  }
}

} // namespace otparam

#endif
