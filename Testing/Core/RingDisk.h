// A triangulated disk made of concentric rings of 6k points (k = 1..rings) around a centre
// point, staggered ring to ring: well-shaped triangles, counter-clockwise. Each point is given
// as (t, azimuth) with t = k / rings in [0, 1]; callers map it to the plane or a sphere.
#ifndef OTPARAM_TESTING_RINGDISK_H
#define OTPARAM_TESTING_RINGDISK_H

#include "Common/Geometry.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace otparam
{
namespace testing
{

struct RingDisk
{
  std::vector<double> t, azimuth;
  std::vector<Triangle> triangles;
};

inline RingDisk makeRingDisk(int rings)
{
  constexpr double Pi = 3.14159265358979323846;
  RingDisk disk;
  disk.t.push_back(0.0);
  disk.azimuth.push_back(0.0);
  std::vector<int> inner = { 0 };
  double innerStart = 0.0;
  for (int k = 1; k <= rings; ++k)
  {
    const int no = 6 * k;
    const double start = (k % 2) * Pi / no;
    std::vector<int> outer;
    for (int j = 0; j < no; ++j)
    {
      outer.push_back(static_cast<int>(disk.t.size()));
      disk.t.push_back(static_cast<double>(k) / rings);
      disk.azimuth.push_back(start + 2.0 * Pi * j / no);
    }
    // Zip the two rings together in order of azimuth.
    const int ni = static_cast<int>(inner.size());
    int i = 0, o = 0;
    while (i < (ni == 1 ? 0 : ni) || o < no)
    {
      const bool alongOuter = o < no &&
        (ni == 1 || i == ni ||
          start + 2.0 * Pi * (o + 1) / no < innerStart + 2.0 * Pi * (i + 1) / ni);
      if (alongOuter)
      {
        disk.triangles.push_back({ inner[i % ni], outer[o], outer[(o + 1) % no] });
        ++o;
      }
      else
      {
        disk.triangles.push_back({ inner[i % ni], outer[o % no], inner[(i + 1) % ni] });
        ++i;
      }
    }
    inner = outer;
    innerStart = start;
  }
  return disk;
}

struct PlanarMesh
{
  std::vector<Vec2> points;
  std::vector<Triangle> triangles;
};

// The unit disk as a flat ring disk: boundary points on the circle. With a `crowding` c > 0,
// ring t at radius exp(-c (1 - t)) instead of t: triangles shrinking towards the centre by e^c,
// as a conformal image's extremity.
inline PlanarMesh makePlanarDisk(int rings, double crowding = 0.0)
{
  const RingDisk disk = makeRingDisk(rings);
  PlanarMesh mesh;
  for (size_t v = 0; v < disk.t.size(); ++v)
  {
    const double r =
      crowding > 0.0 && disk.t[v] > 0.0 ? std::exp(-crowding * (1.0 - disk.t[v])) : disk.t[v];
    mesh.points.push_back({ r * std::cos(disk.azimuth[v]), r * std::sin(disk.azimuth[v]) });
  }
  mesh.triangles = disk.triangles;
  return mesh;
}

// Two narrow Gaussian peaks over a floor: largest / smallest density = contrast (the kind of
// exponential peaks a conformal image of a hand has at its finger tips).
inline double gaussianMixture(Vec2 p, double contrast)
{
  auto bump = [&](Vec2 c, double s) { return std::exp(-dot(p - c, p - c) / (s * s)); };
  return 1.0 + (contrast - 1.0) * std::max(bump({ 0.45, 0.2 }, 0.06), bump({ -0.3, -0.5 }, 0.1));
}

} // namespace testing
} // namespace otparam

#endif
