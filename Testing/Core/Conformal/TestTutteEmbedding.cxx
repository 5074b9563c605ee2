// Tutte's embedding (the sphere's lifted disk start, Pipeline/LiftedDiskStart.h) and the lift
// of a disk onto a cap by Lambert's equal-area projection.
#include "Conformal/TutteEmbedding.h"

#include "Common/SphericalGeometry.h"
#include "Mesh/Folds.h"
#include "RingDisk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace otparam;

namespace
{
constexpr double Pi = 3.14159265358979323846;

// Points on the boundary of the ring disk: those on the unit circle.
std::vector<char> onCircle(const otparam::testing::PlanarMesh& disk)
{
  std::vector<char> fixed(disk.points.size());
  for (size_t v = 0; v < disk.points.size(); ++v)
  {
    fixed[v] = std::abs(norm(disk.points[v]) - 1.0) < 1e-12;
  }
  return fixed;
}
} // namespace

// A triangulated square grid (every quad cut the same way): each inner point is the mean of its
// six neighbours, so with the boundary fixed where it is, the embedding is the grid itself.
TEST(TutteEmbedding, RecoversAGridFromItsBoundary)
{
  constexpr int n = 12;
  std::vector<Vec2> grid;
  std::vector<Triangle> triangles;
  std::vector<char> fixed;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      grid.push_back({ 0.3 * i + 0.1 * j, 0.2 * j }); // sheared: affine images are recovered too
      fixed.push_back(i == 0 || j == 0 || i == n || j == n);
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      triangles.push_back({ a, b, d });
      triangles.push_back({ a, d, c });
    }
  }
  std::vector<Vec2> uv(grid.size(), Vec2{ 5.0, 5.0 });
  for (size_t v = 0; v < grid.size(); ++v)
  {
    if (fixed[v])
    {
      uv[v] = grid[v];
    }
  }
  ASSERT_EQ(tutteEmbedding(triangles, fixed, uv), "");
  for (size_t v = 0; v < grid.size(); ++v)
  {
    EXPECT_LT(norm(uv[v] - grid[v]), 1e-12) << "point " << v;
  }
}

// The boundary moved to random angles on the circle (in their order): no triangle flips, as
// Tutte's theorem says for a convex boundary.
TEST(TutteEmbedding, KeepsEveryTriangleOnAConvexBoundary)
{
  const otparam::testing::PlanarMesh disk = otparam::testing::makePlanarDisk(10);
  const std::vector<char> fixed = onCircle(disk);
  std::vector<int> boundary;
  for (size_t v = 0; v < fixed.size(); ++v)
  {
    if (fixed[v])
    {
      boundary.push_back(static_cast<int>(v));
    }
  }
  // Sorted by angle, then moved to angles drawn in the same order.
  std::sort(boundary.begin(), boundary.end(),
    [&](int a, int b)
    {
      return std::atan2(disk.points[a].y, disk.points[a].x) <
        std::atan2(disk.points[b].y, disk.points[b].x);
    });
  std::mt19937 random(7);
  std::uniform_real_distribution<double> step(0.2, 1.8);
  std::vector<double> angle(boundary.size());
  double sum = 0.0;
  for (double& a : angle)
  {
    sum += step(random);
    a = sum;
  }
  std::vector<Vec2> uv(disk.points.size(), Vec2{ 0.0, 0.0 });
  for (size_t k = 0; k < boundary.size(); ++k)
  {
    const double a = -Pi + 2.0 * Pi * angle[k] / (sum + 1.0);
    uv[boundary[k]] = { std::cos(a), std::sin(a) };
  }
  ASSERT_EQ(tutteEmbedding(disk.triangles, fixed, uv), "");
  EXPECT_FALSE(anyFolded(uv, disk.triangles));
}

TEST(TutteEmbedding, RefusesAPatchWithNoFixedPoint)
{
  const otparam::testing::PlanarMesh disk = otparam::testing::makePlanarDisk(3);
  std::vector<Vec2> uv = disk.points;
  EXPECT_NE(
    tutteEmbedding(disk.triangles, std::vector<char>(uv.size(), 0), uv).find("no fixed point"),
    std::string::npos);
}

// Lambert's projection onto the cap of share k: every point on the unit sphere, a circle of
// radius r at the cap's share k r^2, and the lifted disk's triangles filling the cap's area.
TEST(LiftDiskToCap, IsEqualAreaOntoItsCap)
{
  const double share = 0.37;
  const otparam::testing::PlanarMesh disk = otparam::testing::makePlanarDisk(40);
  std::vector<Vec3> lifted;
  for (const Vec2& w : disk.points)
  {
    lifted.push_back(liftDiskToCap(w, share));
    EXPECT_NEAR(norm(lifted.back()), 1.0, 1e-15);
    const double r2 = dot(w, w);
    EXPECT_NEAR(0.5 * (1.0 - lifted.back().z), share * r2, 1e-15); // cap share above it
  }
  double area = 0.0;
  for (const Triangle& t : disk.triangles)
  {
    const double a = sphericalTriangleArea(lifted[t[0]], lifted[t[1]], lifted[t[2]]);
    EXPECT_GT(a, 0.0);
    area += a;
  }
  // The polygon's chords cut off a little of the cap.
  EXPECT_NEAR(area / (4.0 * Pi * share), 1.0, 2e-3);
  // Near the centre the lift keeps the relative precision of w.
  const Vec3 tiny = liftDiskToCap({ 1e-200, -3e-200 }, share);
  EXPECT_NEAR(tiny.x / 1e-200, 2.0 * std::sqrt(share), 1e-15);
  EXPECT_NEAR(tiny.y / -3e-200, 2.0 * std::sqrt(share), 1e-15);
}
