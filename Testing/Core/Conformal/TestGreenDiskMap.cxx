// The conformal disk map in polar form around a vertex (GreenDiskMap.h): exact maps recovered,
// and a finger's tip resolved far below the usual map's absolute precision.
#include "Conformal/ConformalDiskMap.h"
#include "Conformal/GreenDiskMap.h"
#include "FingerMesh.h"
#include "Mesh/Folds.h"
#include "Mesh/SurfaceMesh.h"
#include "RingDisk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

using namespace otparam;
using namespace otparam::testing;

namespace
{
constexpr double Pi = 3.14159265358979323846;

// The largest distance of the map to the exact one, rotated so that the align vertex matches.
template <class Exact>
double distanceTo(const GreenDiskMap& map, int alignVertex, const Exact& exact)
{
  const std::complex<double> turn =
    std::complex<double>(map.uv[alignVertex].x, map.uv[alignVertex].y) / exact(alignVertex);
  double worst = 0.0;
  for (size_t v = 0; v < map.uv.size(); ++v)
  {
    const std::complex<double> z(map.uv[v].x, map.uv[v].y);
    worst = std::max(worst, std::abs(z - turn * exact(static_cast<int>(v))));
  }
  return worst;
}

SurfaceMesh mapped(const RingDisk& disk, double (*polar)(double))
{
  SurfaceMesh mesh;
  for (size_t v = 0; v < disk.t.size(); ++v)
  {
    const double angle = polar(disk.t[v]);
    mesh.points.push_back({ std::sin(angle) * std::cos(disk.azimuth[v]),
      std::sin(angle) * std::sin(disk.azimuth[v]), std::cos(angle) });
  }
  mesh.triangles = disk.triangles;
  return mesh;
}
} // namespace

// The unit hemisphere with its pole at the centre: the exact map is the stereographic
// projection from the south pole. Measured: 2.4e-3, 9.1e-4, 4.3e-4 at 8, 16, 32 rings (the
// usual map, whose boundary angles are iterated to conformality, 6.6e-5 at 32): the discrete
// Green's function's radii converge a little slower than second order, enough for a start
// that staged transports move anyway.
TEST(GreenDiskMap, HemisphereConvergesToStereographicProjection)
{
  double previous = 1.0;
  for (int rings : { 8, 16, 32 })
  {
    const SurfaceMesh hemisphere =
      mapped(makeRingDisk(rings), [](double t) { return 0.5 * Pi * t; });
    std::vector<int> loop;
    ASSERT_EQ(checkDiskTopology(hemisphere, loop), "");
    const GreenDiskMap map = computeGreenDiskMap(hemisphere, loop, 0);
    ASSERT_TRUE(map.status.ok()) << map.status.error;
    EXPECT_FALSE(anyFolded(map.uv, hemisphere.triangles));
    double radius = 0.0;
    for (int v : loop)
    {
      radius = std::max(radius, std::abs(norm(map.uv[v]) - 1.0));
    }
    EXPECT_LT(radius, 1e-15);
    const double error = distanceTo(map, loop[0],
      [&](int v)
      {
        const Vec3 p = hemisphere.points[v];
        return std::complex<double>(p.x, p.y) / (1.0 + p.z);
      });
    std::printf("hemisphere with %d rings: largest error %.3e\n", rings, error);
    EXPECT_LT(error, 0.5 * previous) << rings << " rings";
    previous = error;
  }
  EXPECT_LT(previous, 6e-4);
}

// The most secluded vertex is the tip of a protrusion: on the finger, the point at its end.
// There the usual map folds (its images ~1e-17 apart at L / rho = 100) and this one resolves
// every ring: radii falling by exp(-2 pi / 24) per ring of the tube down to ~e^-100.
TEST(GreenDiskMap, FingerTipResolvedToTheSmallestRing)
{
  const TriangleSoup soup = diskWithAFinger(100.0);
  SurfaceMesh mesh;
  for (const Vec3& p : soup.points)
  {
    mesh.points.push_back(p);
  }
  for (const auto& t : soup.triangles)
  {
    mesh.triangles.push_back(
      { static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2]) });
  }
  std::vector<int> loop;
  ASSERT_EQ(checkDiskTopology(mesh, loop), "");
  const int tip = static_cast<int>(mesh.points.size()) - 1;
  EXPECT_TRUE(anyFolded(computeConformalDiskMap(mesh, loop, { tip }).uv, mesh.triangles))
    << "the usual map, centred at the tip, no longer folds there: this test shows nothing";
  const GreenDiskMap map = computeGreenDiskMap(mesh, loop);
  ASSERT_TRUE(map.status.ok()) << map.status.error;
  EXPECT_EQ(map.centerVertex, tip);
  EXPECT_FALSE(anyFolded(map.uv, mesh.triangles));
  const int n = 24;
  const auto ringRadius = [&](int ring)
  {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
    {
      sum += norm(map.uv[ring * n + j]) / n;
    }
    return sum;
  };
  const int rings = tip / n;
  // The tube's rings, away from its two ends: their spacing is 2 pi / 24 radii.
  for (int ring = 40; ring + 40 < rings; ring += 25)
  {
    EXPECT_NEAR(ringRadius(ring + 1) / ringRadius(ring), std::exp(-2.0 * Pi / n), 2e-3) << ring;
  }
  EXPECT_LT(ringRadius(rings - 1), 1e-38);
  EXPECT_GT(ringRadius(rings - 1), 1e-50);
}
