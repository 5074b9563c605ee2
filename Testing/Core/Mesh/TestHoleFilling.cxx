// Hole filling on planar disks with 1, 3 and 10 round holes: every loop but the outer one is
// closed (for the sphere every one), the input's points and triangles stay the leading part in
// their order, the result is a disk, and the planar fill covers exactly the holes (fairing a
// planar rim in a plane keeps it planar, so the fill's area is the holes' area).
#include "Mesh/HoleFilling.h"

#include "RingDisk.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace otparam;

namespace
{
struct Hole
{
  Vec2 centre;
  double radius;
};

// The planar ring disk without the triangles whose centroid is in a hole (and the points
// they leave unused).
SurfaceMesh diskWithHoles(const std::vector<Hole>& holes, double& holesArea)
{
  const otparam::testing::PlanarMesh disk = otparam::testing::makePlanarDisk(30);
  SurfaceMesh mesh;
  for (Vec2 p : disk.points)
  {
    mesh.points.push_back({ p.x, p.y, 0.0 });
  }
  holesArea = 0.0;
  for (const Triangle& t : disk.triangles)
  {
    const Vec2 centroid = (1.0 / 3.0) * (disk.points[t[0]] + disk.points[t[1]] + disk.points[t[2]]);
    bool inHole = false;
    for (const Hole& hole : holes)
    {
      inHole = inHole || norm(centroid - hole.centre) < hole.radius;
    }
    if (inHole)
    {
      holesArea += triangleArea(mesh, t);
    }
    else
    {
      mesh.triangles.push_back(t);
    }
  }
  std::vector<std::array<std::int64_t, 3>> triangles;
  for (const Triangle& t : mesh.triangles)
  {
    triangles.push_back({ t[0], t[1], t[2] });
  }
  CompactedMesh compacted;
  compactMesh(mesh.points, triangles, compacted);
  return compacted.mesh;
}

std::vector<Hole> holesOf(int count)
{
  if (count == 1)
  {
    return { { { 0.25, 0.1 }, 0.25 } };
  }
  std::vector<Hole> holes;
  for (int j = 0; j < count; ++j)
  {
    const double angle = 2.0 * 3.14159265358979323846 * j / count;
    holes.push_back({ { 0.55 * std::cos(angle), 0.55 * std::sin(angle) }, 0.05 + 0.04 * (j % 3) });
  }
  return holes;
}
} // namespace

TEST(HoleFilling, ClosesEveryLoopButTheLongest)
{
  for (int count : { 1, 3, 10 })
  {
    SCOPED_TRACE(count);
    double holesArea = 0.0;
    const SurfaceMesh mesh = diskWithHoles(holesOf(count), holesArea);
    SurfaceTopology topology;
    ASSERT_EQ(analyzeSurface(mesh, topology), "");
    ASSERT_EQ(topology.boundaryLoops.size(), static_cast<size_t>(count + 1));

    FilledSurface filled;
    ASSERT_EQ(fillHolesButLongest(mesh, topology.boundaryLoops, filled), "");
    EXPECT_EQ(filled.filledHoles, count);
    for (int v : filled.boundaryLoop)
    {
      EXPECT_NEAR(std::hypot(mesh.points[v].x, mesh.points[v].y), 1.0, 1e-12);
    }
    ASSERT_GT(filled.mesh.triangles.size(), mesh.triangles.size());
    for (size_t v = 0; v < mesh.points.size(); ++v)
    {
      ASSERT_EQ(filled.mesh.points[v].x, mesh.points[v].x);
      ASSERT_EQ(filled.mesh.points[v].y, mesh.points[v].y);
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
    {
      ASSERT_EQ(filled.mesh.triangles[t], mesh.triangles[t]);
    }
    double inputArea = 0.0, fillArea = 0.0;
    for (size_t t = 0; t < filled.mesh.triangles.size(); ++t)
    {
      const double area = triangleArea(filled.mesh, filled.mesh.triangles[t]);
      (t < mesh.triangles.size() ? inputArea : fillArea) += area;
    }
    for (size_t v = mesh.points.size(); v < filled.mesh.points.size(); ++v)
    {
      EXPECT_NEAR(filled.mesh.points[v].z, 0.0, 1e-9); // a planar fill
    }
    EXPECT_NEAR(fillArea, holesArea, 1e-9);
    EXPECT_NEAR(filled.fillAreaFraction, fillArea / (inputArea + fillArea), 1e-12);
    std::vector<int> loop;
    EXPECT_EQ(checkDiskTopology(filled.mesh, loop), "");
    EXPECT_EQ(loop.size(), filled.boundaryLoop.size());
  }
}

TEST(HoleFilling, KeepsTheLongestLoopByLength)
{
  // A hole of radius 0.9 leaves a thin ring: its loop (length ~5.6) is nearly as long as the
  // rim (2 pi), and the rim, the longer, is kept whatever the loops' order.
  double holesArea = 0.0;
  const SurfaceMesh mesh = diskWithHoles({ { { 0.0, 0.0 }, 0.9 } }, holesArea);
  SurfaceTopology topology;
  ASSERT_EQ(analyzeSurface(mesh, topology), "");
  ASSERT_EQ(topology.boundaryLoops.size(), 2u);
  const size_t longest = longestLoop(mesh, topology.boundaryLoops);
  for (int v : topology.boundaryLoops[longest])
  {
    EXPECT_NEAR(std::hypot(mesh.points[v].x, mesh.points[v].y), 1.0, 1e-12);
  }
}

// For the sphere every loop is closed, the rim too: the holed disk becomes a closed genus-0
// surface, its own points and triangles still the leading part.
TEST(HoleFilling, ClosesEveryLoopForTheSphere)
{
  double holesArea = 0.0;
  const SurfaceMesh mesh = diskWithHoles(holesOf(3), holesArea);
  SurfaceTopology topology;
  ASSERT_EQ(analyzeSurface(mesh, topology), "");
  FilledSurface filled;
  ASSERT_EQ(fillHoles(mesh, topology.boundaryLoops, topology.boundaryLoops.size(), filled), "");
  EXPECT_EQ(filled.filledHoles, 4);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    ASSERT_EQ(filled.mesh.triangles[t], mesh.triangles[t]);
  }
  EXPECT_EQ(checkSphereTopology(filled.mesh), "");
}

// A grid cut along its middle row (the triangles above it use copies of the row's inner points:
// a seam whose points are not shared) has a second boundary loop of zero area: a slit, which
// the fill refuses with what to do, instead of closing it with triangles of zero area.
TEST(HoleFilling, RefusesASlit)
{
  constexpr int N = 9, Row = N / 2;
  SurfaceMesh mesh;
  for (int j = 0; j < N; ++j)
  {
    for (int i = 0; i < N; ++i)
    {
      mesh.points.push_back({ static_cast<double>(i), static_cast<double>(j), 0.0 });
    }
  }
  std::vector<int> copy(N * N, -1);
  for (int i = 2; i < N - 2; ++i)
  {
    copy[Row * N + i] = static_cast<int>(mesh.points.size());
    mesh.points.push_back(mesh.points[Row * N + i]);
  }
  for (int j = 0; j + 1 < N; ++j)
  {
    for (int i = 0; i + 1 < N; ++i)
    {
      const int a = j * N + i, b = a + 1, c = a + N + 1, d = a + N;
      for (Triangle t : { Triangle{ a, b, c }, Triangle{ a, c, d } })
      {
        for (int& v : t)
        {
          v = j >= Row && copy[v] >= 0 ? copy[v] : v; // the squares above the row
        }
        mesh.triangles.push_back(t);
      }
    }
  }
  SurfaceTopology topology;
  ASSERT_EQ(analyzeSurface(mesh, topology), "");
  ASSERT_EQ(topology.boundaryLoops.size(), 2u);
  FilledSurface filled;
  const std::string error = fillHolesButLongest(mesh, topology.boundaryLoops, filled);
  EXPECT_NE(error.find("is a slit, not a hole: 10 of its points lie exactly where other "
                       "boundary points are"),
    std::string::npos)
    << error;
  EXPECT_NE(error.find("vtkCleanPolyData"), std::string::npos) << error;
  EXPECT_EQ(slitAmongHoles(mesh, topology.boundaryLoops, 2), error);
}

// The largest hole's share measured by a round disk of its length: exact for a round hole in
// a plane (up to the polygon's chords), 0 without a loop.
TEST(HoleFilling, LargestHoleFractionOfARoundHole)
{
  double holesArea = 0.0;
  const SurfaceMesh mesh = diskWithHoles({ { { 0.0, 0.0 }, 0.5 } }, holesArea);
  SurfaceTopology topology;
  ASSERT_EQ(analyzeSurface(mesh, topology), "");
  // Without the rim the inner loop is the longest: a disk of radius ~0.5 over an annulus of
  // area ~pi (1 - 0.25).
  const std::vector<std::vector<int>> inner = {
    topology.boundaryLoops[1 - longestLoop(mesh, topology.boundaryLoops)]
  };
  double surfaceArea = 0.0;
  for (const Triangle& t : mesh.triangles)
  {
    surfaceArea += triangleArea(mesh, t);
  }
  EXPECT_NEAR(
    largestHoleFraction(mesh, inner), holesArea / surfaceArea, 0.05 * holesArea / surfaceArea);
  EXPECT_EQ(largestHoleFraction(mesh, {}), 0.0);
}
