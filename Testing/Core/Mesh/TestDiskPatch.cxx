// The body patch that the sphere's lifted disk start cuts out (Pipeline/LiftedDiskStart.h).
#include "Mesh/DiskPatch.h"

#include "FingerMesh.h"
#include "SphereMeshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

using namespace otparam;

namespace
{
double areaOf(const SurfaceMesh& mesh, const std::vector<char>& inPatch)
{
  double area = 0.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    area += inPatch.empty() || inPatch[t] ? triangleArea(mesh, mesh.triangles[t]) : 0.0;
  }
  return area;
}

// V - E + F of the marked triangles and their boundary edges (used once).
std::pair<int, int> eulerAndBoundaryEdges(const SurfaceMesh& mesh, const std::vector<char>& in)
{
  std::map<std::pair<int, int>, int> uses;
  std::map<int, int> vertices;
  int faces = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    if (!in[t])
    {
      continue;
    }
    ++faces;
    for (int k = 0; k < 3; ++k)
    {
      const int a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      ++vertices[a];
      ++uses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  int boundary = 0;
  for (const auto& [edge, count] : uses)
  {
    boundary += count == 1;
  }
  return { static_cast<int>(vertices.size()) - static_cast<int>(uses.size()) + faces, boundary };
}

// The finger of TestCrowding (L / rho = 30) closed by a cone below its disk: a body and a
// protrusion three times longer than the body is wide.
SurfaceMesh closedFinger()
{
  const TriangleSoup soup = otparam::testing::diskWithAFinger(30.0);
  SurfaceMesh mesh;
  mesh.points = soup.points;
  for (const auto& t : soup.triangles)
  {
    mesh.triangles.push_back(
      { static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2]) });
  }
  const int apex = static_cast<int>(mesh.points.size());
  mesh.points.push_back({ 0.0, 0.0, -1.0 });
  constexpr int n = 24; // the rim: the first ring, points 0..23, counter-clockwise from above
  for (int j = 0; j < n; ++j)
  {
    mesh.triangles.push_back({ (j + 1) % n, j, apex });
  }
  return mesh;
}
} // namespace

// On a sphere: the smallest patch of whole rings around a pole holding the share, a disk.
TEST(DiskPatch, GrowsRingsUntilItHoldsItsShare)
{
  const SurfaceMesh sphere = otparam::testing::revolutionSurface(
    [](double z) { return std::sqrt(std::max(0.0, 1.0 - z * z)); }, 40, 48);
  const double total = areaOf(sphere, {});
  const std::vector<char> patch = growDiskPatch(sphere, 0, 0.3);
  ASSERT_FALSE(patch.empty());
  const double share = areaOf(sphere, patch) / total;
  EXPECT_GE(share, 0.3);
  EXPECT_LT(share, 0.35); // one ring (of 40) more than needed at most
  const auto [euler, boundaryEdges] = eulerAndBoundaryEdges(sphere, patch);
  EXPECT_EQ(euler, 1);
  EXPECT_EQ(boundaryEdges, 48);
}

// Grown on a tube, a patch stops where its rings would close around it (an annulus): the
// largest disk before that.
TEST(DiskPatch, StopsBeforeClosingAroundATube)
{
  const SurfaceMesh finger = closedFinger();
  int onTube = -1;
  for (size_t v = 0; v < finger.points.size() && onTube < 0; ++v)
  {
    onTube = std::abs(finger.points[v].z - 3.0) < 0.03 ? static_cast<int>(v) : -1;
  }
  ASSERT_GE(onTube, 0);
  const std::vector<char> patch = growDiskPatch(finger, onTube, 0.5);
  ASSERT_FALSE(patch.empty());
  EXPECT_EQ(eulerAndBoundaryEdges(finger, patch).first, 1);
  EXPECT_LT(areaOf(finger, patch) / areaOf(finger, {}), 0.1);
}

// The body patch lies in the body (the disk and the cone below it), not on the finger.
TEST(DiskPatch, BodyPatchAvoidsTheProtrusion)
{
  const SurfaceMesh finger = closedFinger();
  int centre = -1;
  const std::vector<char> patch = bodyPatch(finger, 0.3, centre);
  ASSERT_FALSE(patch.empty());
  ASSERT_GE(centre, 0);
  EXPECT_LE(finger.points[centre].z, 0.0);
  EXPECT_GE(areaOf(finger, patch) / areaOf(finger, {}), 0.8 * 0.3);
  EXPECT_EQ(eulerAndBoundaryEdges(finger, patch).first, 1);
  for (size_t t = 0; t < finger.triangles.size(); ++t)
  {
    if (patch[t])
    {
      for (int v : finger.triangles[t])
      {
        EXPECT_LT(finger.points[v].z, 1.0) << "the patch climbs the finger";
      }
    }
  }
}
