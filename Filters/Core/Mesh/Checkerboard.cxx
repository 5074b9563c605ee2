#include "Mesh/Checkerboard.h"

#include <algorithm>
#include <cmath>

namespace otparam
{
namespace
{
// Index of the cell of [lo, lo + cells * width) holding x, clamped so the closed end counts.
long long cellIndex(double x, double lo, double width, int cells)
{
  const double i = std::floor((x - lo) / width);
  return static_cast<long long>(std::clamp(i, 0.0, static_cast<double>(cells - 1)));
}
} // namespace

std::vector<int> diskCheckerboard(
  const std::vector<Triangle>& triangles, const std::vector<Vec2>& uv, int squaresPerDiameter)
{
  const int n = std::max(1, squaresPerDiameter);
  const double side = 2.0 / n;
  std::vector<int> parity(triangles.size(), 0);
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    const Vec2 c = (1.0 / 3.0) * (uv[triangles[t][0]] + uv[triangles[t][1]] + uv[triangles[t][2]]);
    if (std::isfinite(c.x) && std::isfinite(c.y))
    {
      parity[t] =
        static_cast<int>((cellIndex(c.x, -1.0, side, n) + cellIndex(c.y, -1.0, side, n)) % 2);
    }
  }
  return parity;
}

std::vector<int> sphereCheckerboard(
  const std::vector<Triangle>& triangles, const std::vector<Vec3>& sphere, int sectors)
{
  const int longitudes = std::max(2, sectors + sectors % 2);
  const int bands = longitudes / 2;
  std::vector<int> parity(triangles.size(), 0);
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    const Vec3 sum = sphere[triangles[t][0]] + sphere[triangles[t][1]] + sphere[triangles[t][2]];
    const double length = norm(sum);
    if (!(length > 0.0) || !std::isfinite(length))
    {
      continue;
    }
    const Vec3 c = (1.0 / length) * sum;
    const long long sector =
      cellIndex(std::atan2(c.y, c.x), -M_PI, 2.0 * M_PI / longitudes, longitudes);
    const long long band = cellIndex(c.z, -1.0, 2.0 / bands, bands);
    parity[t] = static_cast<int>((sector + band) % 2);
  }
  return parity;
}

} // namespace otparam
