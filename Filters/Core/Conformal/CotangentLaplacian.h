// The cotangent Laplacian of a triangulation given by its edge lengths, shared by the disk and
// the sphere conformal maps.
#ifndef OTPARAM_CONFORMAL_COTANGENTLAPLACIAN_H
#define OTPARAM_CONFORMAL_COTANGENTLAPLACIAN_H

#include "Mesh/IntrinsicDelaunay.h"

#include <Eigen/Sparse>

#include <vector>

namespace otparam
{

// The n x n cotangent Laplacian (positive semi-definite: diagonal = sum of the half-cotangent
// weights, off-diagonal = minus the weight), both triangles, from the triangulation's edge
// lengths (the mesh's own, or those of its intrinsic Delaunay triangulation).
inline Eigen::SparseMatrix<double> cotangentLaplacian(
  const IntrinsicTriangulation& triangulation, int n)
{
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(12 * triangulation.triangles.size());
  for (size_t t = 0; t < triangulation.triangles.size(); ++t)
  {
    const Triangle& tri = triangulation.triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      const double half = halfCotangent(triangulation.lengths[t], k);
      const int a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
      entries.emplace_back(a, b, -half);
      entries.emplace_back(b, a, -half);
      entries.emplace_back(a, a, half);
      entries.emplace_back(b, b, half);
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

} // namespace otparam

#endif
