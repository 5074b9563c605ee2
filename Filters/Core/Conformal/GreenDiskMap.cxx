#include "Conformal/GreenDiskMap.h"

#include "Conformal/CotangentLaplacian.h"

#include "Mesh/IntrinsicDelaunay.h"

#include "Common/SparseCholesky.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <deque>
#include <unordered_map>

namespace otparam
{
namespace
{

constexpr double TwoPi = 6.283185307179586476925286766559;

IntrinsicTriangulation intrinsicTriangulationOf(const SurfaceMesh& mesh)
{
  return intrinsicDelaunay(mesh.triangles, edgeLengthsOf(mesh.points, mesh.triangles));
}

double heronArea(const std::array<double, 3>& l)
{
  const double s = 0.5 * (l[0] + l[1] + l[2]);
  return std::sqrt(std::max(0.0, s * (s - l[0]) * (s - l[1]) * (s - l[2])));
}

// The harmonic conjugate of u per triangle: across an interior edge a -> b (the triangle on its
// left), it changes by minus the edge's weight times u_b - u_a. Found breadth first over the
// dual graph; the one loop that does not close (around the pole) turns by one period, which
// the map reads as an angle.
std::vector<double> conjugatePerTriangle(
  const IntrinsicTriangulation& intrinsic, const std::vector<double>& u)
{
  const std::vector<Triangle>& triangles = intrinsic.triangles;
  const auto key = [](int a, int b)
  { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b); };
  std::unordered_map<std::uint64_t, int> leftOf;
  std::unordered_map<std::uint64_t, double> weight; // per directed edge, both triangles' halves
  leftOf.reserve(3 * triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = triangles[t][(k + 1) % 3], b = triangles[t][(k + 2) % 3];
      leftOf[key(a, b)] = static_cast<int>(t);
      const double half = halfCotangent(intrinsic.lengths[t], k);
      weight[key(a, b)] += half;
      weight[key(b, a)] += half;
    }
  }
  std::vector<double> conjugate(triangles.size(), std::nan(""));
  std::deque<int> queue;
  for (size_t seed = 0; seed < triangles.size(); ++seed)
  {
    if (!std::isnan(conjugate[seed]))
    {
      continue;
    }
    conjugate[seed] = 0.0;
    queue.push_back(static_cast<int>(seed));
    while (!queue.empty())
    {
      const int t = queue.front();
      queue.pop_front();
      for (int k = 0; k < 3; ++k)
      {
        const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
        const auto across = leftOf.find(key(b, a));
        if (across == leftOf.end() || !std::isnan(conjugate[across->second]))
        {
          continue;
        }
        conjugate[across->second] = conjugate[t] - weight[key(a, b)] * (u[b] - u[a]);
        queue.push_back(across->second);
      }
    }
  }
  return conjugate;
}

// The Dirichlet block of the cotangent Laplacian: the interior vertices' rows and columns, in
// `interiorIndex` numbering (-1 on the boundary); lower triangle.
Eigen::SparseMatrix<double> dirichletLaplacian(
  const IntrinsicTriangulation& intrinsic, const std::vector<int>& interiorIndex, int interior)
{
  const Eigen::SparseMatrix<double> laplacian =
    cotangentLaplacian(intrinsic, static_cast<int>(interiorIndex.size()));
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < laplacian.outerSize(); ++k)
  {
    for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian, k); it; ++it)
    {
      const int i = interiorIndex[it.row()], j = interiorIndex[it.col()];
      if (i >= 0 && j >= 0 && i >= j)
      {
        entries.emplace_back(i, j, it.value());
      }
    }
  }
  Eigen::SparseMatrix<double> dirichlet(interior, interior);
  dirichlet.setFromTriplets(entries.begin(), entries.end());
  return dirichlet;
}

// The interior vertex where the torsion function (L tau = vertex areas, 0 on the boundary: a
// random walk's expected exit time) is largest.
int mostSecludedVertex(const IntrinsicTriangulation& intrinsic, const SparseCholesky& dirichlet,
  const std::vector<int>& interiorIndex)
{
  Eigen::VectorXd area = Eigen::VectorXd::Zero(dirichlet.size());
  for (size_t t = 0; t < intrinsic.triangles.size(); ++t)
  {
    for (int v : intrinsic.triangles[t])
    {
      if (interiorIndex[v] >= 0)
      {
        area[interiorIndex[v]] += heronArea(intrinsic.lengths[t]) / 3.0;
      }
    }
  }
  const Eigen::VectorXd exitTime = dirichlet.solve(area);
  Eigen::Index deepest = 0;
  exitTime.maxCoeff(&deepest);
  return static_cast<int>(
    std::find(interiorIndex.begin(), interiorIndex.end(), static_cast<int>(deepest)) -
    interiorIndex.begin());
}

// Each vertex's direction: the mean of its triangles' conjugates (as unit vectors) weighted by
// their corner angles there (unweighted, the uneven fans of a ring mesh biased it: a
// hemisphere's map was 5.3e-3 from the exact one at 32 rings instead of 4.3e-4).
std::vector<std::complex<double>> vertexDirections(
  const IntrinsicTriangulation& intrinsic, const std::vector<double>& conjugate, int n)
{
  std::vector<std::complex<double>> direction(n, 0.0);
  for (size_t t = 0; t < intrinsic.triangles.size(); ++t)
  {
    const auto& l = intrinsic.lengths[t];
    for (int k = 0; k < 3; ++k)
    {
      const double a = l[k], b = l[(k + 1) % 3], c = l[(k + 2) % 3];
      const double corner =
        std::acos(std::clamp((b * b + c * c - a * a) / (2.0 * b * c), -1.0, 1.0));
      direction[intrinsic.triangles[t][k]] += std::polar(corner, conjugate[t]);
    }
  }
  return direction;
}

} // namespace

GreenDiskMap computeGreenDiskMap(
  const SurfaceMesh& mesh, const std::vector<int>& boundaryLoop, int centerVertex, int alignVertex)
{
  GreenDiskMap result;
  const int n = static_cast<int>(mesh.points.size());
  std::vector<int> interiorIndex(n, 0);
  for (int v : boundaryLoop)
  {
    interiorIndex[v] = -1;
  }
  int interior = 0;
  for (int v = 0; v < n; ++v)
  {
    interiorIndex[v] = interiorIndex[v] < 0 ? -1 : interior++;
  }
  if (interior == 0 || boundaryLoop.empty() || centerVertex >= n ||
    (centerVertex >= 0 && interiorIndex[centerVertex] < 0))
  {
    result.status.error = "the centre of the crowded map must be an interior point";
    return result;
  }
  const IntrinsicTriangulation intrinsic = intrinsicTriangulationOf(mesh);
  SparseCholesky dirichlet;
  if (!dirichlet.compute(dirichletLaplacian(intrinsic, interiorIndex, interior)))
  {
    result.status.error =
      "the cotangent Laplacian could not be factored for the crowded map (degenerate triangles?)";
    return result;
  }
  result.centerVertex =
    centerVertex >= 0 ? centerVertex : mostSecludedVertex(intrinsic, dirichlet, interiorIndex);
  Eigen::VectorXd pole = Eigen::VectorXd::Zero(interior);
  pole[interiorIndex[result.centerVertex]] = 1.0;
  const Eigen::VectorXd green = dirichlet.solve(pole);
  std::vector<double> logRadius(n, 0.0);
  for (int v = 0; v < n; ++v)
  {
    logRadius[v] = interiorIndex[v] >= 0 ? -TwoPi * green[interiorIndex[v]] : 0.0;
  }
  const std::vector<std::complex<double>> direction =
    vertexDirections(intrinsic, conjugatePerTriangle(intrinsic, logRadius), n);
  const int align =
    alignVertex >= 0 ? alignVertex : *std::min_element(boundaryLoop.begin(), boundaryLoop.end());
  const std::complex<double> turn = std::conj(direction[align]) / std::abs(direction[align]);
  result.uv.assign(n, Vec2{ 0.0, 0.0 });
  for (int v = 0; v < n; ++v)
  {
    if (v != result.centerVertex && std::abs(direction[v]) > 0.0)
    {
      const std::complex<double> z =
        std::exp(logRadius[v]) * (direction[v] * turn) / std::abs(direction[v] * turn);
      result.uv[v] = { z.real(), z.imag() };
    }
  }
  return result;
}

} // namespace otparam
