// The checkerboards through a parameterization: squares alternate, and the two colours share
// the domain's area equally (equal-area squares on the disk, equal-area sector-band cells on
// the sphere), measured on fine meshes with the identity map.
#include "Mesh/Checkerboard.h"

#include "RingDisk.h"
#include "SphereMeshes.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace otparam;

namespace
{
double planarArea(Vec2 a, Vec2 b, Vec2 c)
{
  return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}
} // namespace

TEST(Checkerboard, DiskSquaresAlternateAndHalveTheArea)
{
  const otparam::testing::PlanarMesh disk = otparam::testing::makePlanarDisk(60);
  const std::vector<int> parity = diskCheckerboard(disk.triangles, disk.points, 8);
  ASSERT_EQ(parity.size(), disk.triangles.size());
  double total = 0.0, ones = 0.0;
  for (std::size_t t = 0; t < parity.size(); ++t)
  {
    const Triangle& tri = disk.triangles[t];
    const double area = planarArea(disk.points[tri[0]], disk.points[tri[1]], disk.points[tri[2]]);
    total += area;
    ones += parity[t] * area;
  }
  EXPECT_NEAR(ones / total, 0.5, 0.01);

  // Neighbouring squares differ; the closed right and top edges belong to the last square.
  const std::vector<Vec2> uv = { { 0.1, 0.1 }, { 0.2, 0.1 }, { 0.1, 0.2 }, { 0.35, 0.1 },
    { 0.45, 0.1 }, { 0.35, 0.2 }, { 1.0, 1.0 }, { 1.0, 1.0 }, { 1.0, 1.0 } };
  const std::vector<int> three = diskCheckerboard({ { 0, 1, 2 }, { 3, 4, 5 }, { 6, 7, 8 } }, uv, 8);
  EXPECT_NE(three[0], three[1]);
  EXPECT_EQ(three[2], (7 + 7) % 2);
}

TEST(Checkerboard, SphereCellsAlternateAndHalveTheArea)
{
  const SurfaceMesh sphere =
    otparam::testing::convexHullMesh(otparam::testing::fibonacciSphere(20000));
  const std::vector<int> parity = sphereCheckerboard(sphere.triangles, sphere.points, 12);
  double total = 0.0, ones = 0.0;
  for (std::size_t t = 0; t < parity.size(); ++t)
  {
    const Triangle& tri = sphere.triangles[t];
    const Vec3 a = sphere.points[tri[0]], b = sphere.points[tri[1]], c = sphere.points[tri[2]];
    const double area = 0.5 * norm(cross(b - a, c - a));
    total += area;
    ones += parity[t] * area;
  }
  EXPECT_NEAR(ones / total, 0.5, 0.01);

  // The equator and the meridian at longitude 0 are cell edges: across either the value changes.
  const auto at = [](double longitude, double z)
  {
    const double r = std::sqrt(1.0 - z * z);
    return Vec3{ r * std::cos(longitude), r * std::sin(longitude), z };
  };
  const std::vector<Vec3> points = { at(0.1, 0.1), at(0.1, 0.1), at(0.1, 0.1), at(0.1, -0.1),
    at(0.1, -0.1), at(0.1, -0.1), at(-0.1, 0.1), at(-0.1, 0.1), at(-0.1, 0.1) };
  const std::vector<int> three =
    sphereCheckerboard({ { 0, 1, 2 }, { 3, 4, 5 }, { 6, 7, 8 } }, points, 12);
  EXPECT_NE(three[0], three[1]);
  EXPECT_NE(three[0], three[2]);
}
