// A unit disk with a finger, the crowding test surface (Testing/Python/TestCrowding.py's), for
// the core's tests of the staged transport and of the centred conformal map.
#ifndef OTPARAM_TESTING_FINGERMESH_H
#define OTPARAM_TESTING_FINGERMESH_H

#include "Mesh/SurfaceMesh.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace otparam
{
namespace testing
{

// A unit disk with a finger: a tube of radius rho and length L (capped) rising from a circle of
// radius rho, rings of n points (Testing/Python/TestCrowding.py's surface). The conformal map
// crowds the finger into a part of the disk whose area density grows like exp(2 L / rho).
inline TriangleSoup diskWithAFinger(double lengthOverRadius, double rho = 0.2, int n = 24)
{
  constexpr double Pi = 3.14159265358979323846;
  const double h = 2.0 * Pi / n;
  std::vector<std::pair<double, double>> rings; // (r, z)
  for (double r = 1.0; r > rho * (1.0 + 0.5 * h); r *= std::exp(-h))
  {
    rings.emplace_back(r, 0.0);
  }
  const double length = lengthOverRadius * rho;
  for (double z = 0.0; z < length; z += h * rho)
  {
    rings.emplace_back(rho, z);
  }
  const int cap = std::max(2, static_cast<int>(std::lround((Pi / 2.0) / h)));
  for (int k = 0; k < cap; ++k)
  {
    const double a = (static_cast<double>(k) / cap) * Pi / 2.0;
    rings.emplace_back(rho * std::cos(a), length + rho * std::sin(a));
  }
  TriangleSoup soup;
  for (size_t k = 0; k < rings.size(); ++k)
  {
    const double offset = 0.5 * static_cast<double>(k % 2);
    for (int j = 0; j < n; ++j)
    {
      const double a = 2.0 * Pi * (j + offset) / n;
      soup.points.push_back(
        { rings[k].first * std::cos(a), rings[k].first * std::sin(a), rings[k].second });
    }
  }
  for (std::int64_t k = 0; k + 1 < static_cast<std::int64_t>(rings.size()); ++k)
  {
    const std::int64_t a0 = k * n, b0 = (k + 1) * n;
    for (std::int64_t j = 0; j < n; ++j)
    {
      const std::int64_t j1 = (j + 1) % n;
      if (k % 2 == 0)
      {
        soup.triangles.push_back({ a0 + j, b0 + j, a0 + j1 });
        soup.triangles.push_back({ a0 + j1, b0 + j, b0 + j1 });
      }
      else
      {
        soup.triangles.push_back({ a0 + j, b0 + j, b0 + j1 });
        soup.triangles.push_back({ a0 + j, b0 + j1, a0 + j1 });
      }
    }
  }
  const std::int64_t tip = static_cast<std::int64_t>(soup.points.size());
  soup.points.push_back({ 0.0, 0.0, length + rho });
  const std::int64_t last = tip - n;
  for (std::int64_t j = 0; j < n; ++j)
  {
    soup.triangles.push_back({ last + j, tip, last + (j + 1) % n });
  }
  return soup;
}

} // namespace testing
} // namespace otparam

#endif
