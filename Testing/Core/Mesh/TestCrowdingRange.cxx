// The crowding measures of the staged transport (Mesh/DistortionMetrics.h): densities at shares
// of the surface's area, and the range over the bulk of the surface that a sliver cannot set.
#include "Mesh/DistortionMetrics.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace otparam;

namespace
{
// An n x n grid of unit squares in the plane z = 0, two triangles each (so every triangle has
// area 1/2), triangle 2 (i + n j) and 2 (i + n j) + 1 in cell (i, j).
SurfaceMesh grid(int n)
{
  SurfaceMesh mesh;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      mesh.points.push_back({ double(i), double(j), 0.0 });
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const int a = i + (n + 1) * j, b = a + 1, c = a + n + 2, d = a + n + 1;
      mesh.triangles.push_back({ a, b, c });
      mesh.triangles.push_back({ a, c, d });
    }
  }
  return mesh;
}
} // namespace

TEST(CrowdingRange, DensitiesAtAreaSharesWeighTrianglesByTheirArea)
{
  // 200 triangles of equal area with densities 1..200 (in a shuffled order).
  const SurfaceMesh mesh = grid(10);
  std::vector<double> density(mesh.triangles.size());
  for (size_t t = 0; t < density.size(); ++t)
  {
    density[t] = double((t * 77) % 200 + 1);
  }
  const std::vector<double> at = densitiesAtAreaShares(mesh, density, { 0.01, 0.5, 0.999, 1.0 });
  EXPECT_EQ(at[0], 2.0); // 1% of 200 triangles: the second
  EXPECT_EQ(at[1], 100.0);
  EXPECT_EQ(at[2], 200.0);
  EXPECT_EQ(at[3], 200.0);

  // One large triangle holding 99% of the area: every share from 1% on lies in it.
  SurfaceMesh weighted = mesh;
  weighted.points.push_back({ 0.0, 0.0, 0.0 });
  weighted.points.push_back({ 1e4, 0.0, 0.0 });
  weighted.points.push_back({ 0.0, 2e3, 0.0 }); // area 1e7 against 100
  const int first = static_cast<int>(weighted.points.size()) - 3;
  weighted.triangles.push_back({ first, first + 1, first + 2 });
  std::vector<double> withLarge = density;
  withLarge.push_back(150.5);
  EXPECT_EQ(densitiesAtAreaShares(weighted, withLarge, { 0.01 })[0], 150.5);
  EXPECT_EQ(densitiesAtAreaShares(weighted, withLarge, { 0.5 })[0], 150.5);
}

TEST(CrowdingRange, ASliverDoesNotSetTheRange)
{
  // A density growing like exp(x) along a strip, as along a crowded finger: a range of e^20.
  const int n = 40;
  const SurfaceMesh mesh = grid(n);
  std::vector<double> density(mesh.triangles.size());
  for (size_t t = 0; t < density.size(); ++t)
  {
    const int i = static_cast<int>(t / 2) % n;
    density[t] = std::exp(0.5 * i);
  }
  const double smooth = rangeOf(density);
  EXPECT_NEAR(smooth, std::exp(0.5 * (n - 1)), 1e-6 * smooth);
  EXPECT_EQ(crowdingRange(mesh, density), smooth); // within CrowdedDensityRange: as it is

  // Past CrowdedDensityRange the range is the largest value over the one at 1% of the
  // surface: the first column of cells holds 2.5% of it at density 1.
  std::vector<double> crowded = density;
  crowded[1] = 1e13;
  EXPECT_DOUBLE_EQ(crowdingRange(mesh, crowded), 1e13);

  // A sliver far below the rest (one triangle of 3200 at 1e-20) makes the whole range 3e28; the
  // bulk's is the density's own.
  std::vector<double> withSliver = density;
  withSliver[5] = 1e-20;
  EXPECT_GT(rangeOf(withSliver), 1e28);
  EXPECT_DOUBLE_EQ(crowdingRange(mesh, withSliver), smooth);
  EXPECT_LT(crowdingRange(mesh, withSliver), CrowdedDensityRange);
}
