// The folds of a map, as the staged transport meets them (a crowded finger's conformal image):
// a disk stage samples the unfolded part, a sphere stage the sphere with each folded patch
// healed by a fan. (The rims no fan heals, triangulated by CGAL's hole filling, are met by
// Testing/Python/TestCrowding.py's closed finger from L / rho = 38 on, which fails without.)
#include "Mesh/Folds.h"

#include "Common/SegmentCrossings.h"
#include "Common/SphericalGeometry.h"
#include "RingDisk.h"
#include "SphereMeshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

using namespace otparam;

namespace
{
constexpr double Pi = 3.14159265358979323846;

// The most boundary edges (edges of one kept triangle) at any vertex: 2 on a domain without
// pinches.
int mostBoundaryEdgesAtAVertex(
  const std::vector<Triangle>& triangles, const std::vector<bool>& kept, std::size_t points)
{
  std::set<std::pair<int, int>> edges;
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    for (int k = 0; kept[t] && k < 3; ++k)
    {
      edges.insert({ triangles[t][k], triangles[t][(k + 1) % 3] });
    }
  }
  std::vector<int> count(points, 0);
  int most = 0;
  for (const auto& [a, b] : edges)
  {
    if (!edges.count({ b, a }))
    {
      most = std::max({ most, ++count[a], ++count[b] });
    }
  }
  return most;
}
} // namespace

TEST(Folds, UnfoldedPartLeavesOutTheFoldAndWhatWouldPinch)
{
  // A ring disk with one interior point pushed through its neighbours: its star folds.
  const auto disk = otparam::testing::makePlanarDisk(12);
  std::vector<Vec2> uv = disk.points;
  const int moved = 40;
  uv[moved] = 0.55 * uv[moved]; // past the ring inside it
  std::size_t folded = 0;
  for (const Triangle& t : disk.triangles)
  {
    folded += positive(uv, t) ? 0 : 1;
  }
  ASSERT_GT(folded, 0u);
  const std::vector<bool> kept = unfoldedPart(uv, disk.triangles);
  std::size_t keptCount = 0;
  for (size_t t = 0; t < kept.size(); ++t)
  {
    EXPECT_TRUE(!kept[t] || positive(uv, disk.triangles[t])) << "triangle " << t;
    keptCount += kept[t] ? 1 : 0;
  }
  EXPECT_LE(mostBoundaryEdgesAtAVertex(disk.triangles, kept, uv.size()), 2);
  EXPECT_GE(keptCount, disk.triangles.size() - 4 * folded - 12); // only around the fold

  // A map without folds is kept whole.
  const std::vector<bool> all = unfoldedPart(disk.points, disk.triangles);
  EXPECT_EQ(std::count(all.begin(), all.end(), true), static_cast<long>(disk.triangles.size()));

  // A hexagon whose two opposite triangles are clockwise: the four others would meet at the
  // centre in two fans, so every triangle there goes.
  std::vector<Vec2> hexagon{ { 0.0, 0.0 } };
  for (int k = 0; k < 6; ++k)
  {
    hexagon.push_back({ std::cos(k * Pi / 3.0), std::sin(k * Pi / 3.0) });
  }
  std::vector<Triangle> fan;
  for (int k = 0; k < 6; ++k)
  {
    const int a = 1 + k, b = 1 + (k + 1) % 6;
    fan.push_back(k % 3 == 1 ? Triangle{ 0, b, a } : Triangle{ 0, a, b });
  }
  const std::vector<bool> pinched = unfoldedPart(hexagon, fan);
  EXPECT_EQ(std::count(pinched.begin(), pinched.end(), true), 0);
}

TEST(Folds, UnfoldedPartIsPeeledUntilItsBoundaryDoesNotCross)
{
  // A ring disk with a point of the ring inside the circle thrown out past it: some triangles
  // of its star turn clockwise, others stay counter-clockwise but lie across the circle's
  // edges, so the boundary of the positive triangles crosses itself (CGAL's mesher crashed on
  // such a domain: a crowded finger's stage map). The unfolded part leaves those out too.
  const auto disk = otparam::testing::makePlanarDisk(12);
  std::vector<Vec2> uv = disk.points;
  const int moved = 331;
  ASSERT_NEAR(norm(uv[moved]), 11.0 / 12.0, 1e-12);
  uv[moved] = 1.3 * uv[moved];
  const auto boundaryOf = [&](const std::vector<bool>& kept)
  {
    std::set<std::pair<int, int>> edges;
    for (size_t t = 0; t < kept.size(); ++t)
    {
      for (int k = 0; kept[t] && k < 3; ++k)
      {
        edges.insert({ disk.triangles[t][k], disk.triangles[t][(k + 1) % 3] });
      }
    }
    std::vector<std::pair<int, int>> boundary;
    for (const auto& [a, b] : edges)
    {
      if (!edges.count({ b, a }))
      {
        boundary.push_back({ a, b });
      }
    }
    return boundary;
  };
  std::vector<bool> positiveOnes(disk.triangles.size());
  for (size_t t = 0; t < positiveOnes.size(); ++t)
  {
    positiveOnes[t] = positive(uv, disk.triangles[t]);
  }
  ASSERT_FALSE(crossingSegments(uv, boundaryOf(positiveOnes)).empty());
  EXPECT_FALSE(crossingSegments(uv, boundaryOf(unfoldedPart(uv, disk.triangles))).empty());
  const std::vector<bool> kept = unfoldedPart(uv, disk.triangles, true);
  EXPECT_TRUE(crossingSegments(uv, boundaryOf(kept)).empty());
  EXPECT_LE(mostBoundaryEdgesAtAVertex(disk.triangles, kept, uv.size()), 2);
  std::size_t keptCount = 0;
  for (size_t t = 0; t < kept.size(); ++t)
  {
    EXPECT_TRUE(!kept[t] || positive(uv, disk.triangles[t])) << "triangle " << t;
    keptCount += kept[t] ? 1 : 0;
  }
  EXPECT_GE(keptCount, disk.triangles.size() - 60); // only around the moved point
}

namespace
{
// A healed sphere: every triangle positive, every edge once in each direction, the whole
// sphere covered.
void expectClosedAndPositive(const std::vector<Vec3>& x, const std::vector<Triangle>& triangles)
{
  std::set<std::pair<int, int>> edges;
  double area = 0.0;
  for (const Triangle& t : triangles)
  {
    const double a = sphericalTriangleArea(x[t[0]], x[t[1]], x[t[2]]);
    EXPECT_GT(a, 0.0);
    area += a;
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_TRUE(edges.insert({ t[k], t[(k + 1) % 3] }).second);
    }
  }
  for (const auto& [a, b] : edges)
  {
    EXPECT_TRUE(edges.count({ b, a })) << "edge " << a << "-" << b << " is on a border";
  }
  EXPECT_NEAR(area, 4.0 * Pi, 1e-9);
}

std::size_t notPositive(const std::vector<Vec3>& x, const std::vector<Triangle>& triangles)
{
  std::size_t bad = 0;
  for (const Triangle& t : triangles)
  {
    bad += sphericalTriangleArea(x[t[0]], x[t[1]], x[t[2]]) > 0.0 ? 0 : 1;
  }
  return bad;
}
} // namespace

TEST(Folds, HealedSphereIsClosedAndPositive)
{
  const std::vector<Vec3> points = otparam::testing::fibonacciSphere(400);
  const SurfaceMesh hull = otparam::testing::convexHullMesh(points);
  // One point pushed far past a neighbour folds its star; another collapsed onto its
  // neighbour makes its triangles degenerate.
  for (const bool collapse : { false, true })
  {
    std::vector<Vec3> x = points;
    const Triangle& first = hull.triangles[100];
    x[first[0]] = collapse ? x[first[1]] : normalized(3.0 * x[first[1]] - 2.0 * x[first[0]]);
    std::vector<Triangle> triangles = hull.triangles;
    std::vector<double> density(triangles.size(), 1.0);
    ASSERT_GT(notPositive(x, triangles), 0u);
    healSphereFolds(x, triangles, density);
    EXPECT_EQ(x.size(), points.size() + 1); // the fan's centre
    EXPECT_EQ(density.size(), triangles.size());
    expectClosedAndPositive(x, triangles);
  }
}

// Folds on opposite sides of the sphere (a stage's composition leaves dozens): no one patch
// around both has a single loop for a rim, so each is healed by its own fan.
TEST(Folds, FoldsApartAreHealedApart)
{
  const std::vector<Vec3> points = otparam::testing::fibonacciSphere(400);
  const SurfaceMesh hull = otparam::testing::convexHullMesh(points);
  std::vector<Vec3> x = points;
  int opposite = 0;
  for (size_t t = 0; t < hull.triangles.size(); ++t)
  {
    const Vec3 c = x[hull.triangles[t][0]];
    if (dot(c, x[hull.triangles[100][0]]) <
      dot(x[hull.triangles[opposite][0]], x[hull.triangles[100][0]]))
    {
      opposite = static_cast<int>(t);
    }
  }
  for (const int t : { 100, opposite })
  {
    const Triangle& fold = hull.triangles[t];
    x[fold[0]] = normalized(3.0 * x[fold[1]] - 2.0 * x[fold[0]]);
  }
  std::vector<Triangle> triangles = hull.triangles;
  std::vector<double> density(triangles.size(), 1.0);
  ASSERT_GT(notPositive(x, triangles), 1u);
  healSphereFolds(x, triangles, density);
  EXPECT_EQ(x.size(), points.size() + 2); // one fan's centre each
  EXPECT_EQ(density.size(), triangles.size());
  expectClosedAndPositive(x, triangles);
}
