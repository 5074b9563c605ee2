#include "Mesh/DistortionMetrics.h"

#include "Common/SphericalGeometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>

namespace otparam
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double TinyArea = 1e-300;

double signedArea(Vec2 a, Vec2 b, Vec2 c)
{
  return 0.5 * cross(b - a, c - a);
}

// Unsigned corner angles of a triangle (at vertex 0, 1, 2).
std::array<double, 3> cornerAngles(Vec2 a, Vec2 b, Vec2 c)
{
  auto at = [](Vec2 p, Vec2 q, Vec2 r)
  {
    const Vec2 u = q - p, v = r - p;
    return std::atan2(std::abs(cross(u, v)), dot(u, v));
  };
  return { at(a, b, c), at(b, c, a), at(c, a, b) };
}

std::array<double, 3> cornerAngles(Vec3 a, Vec3 b, Vec3 c)
{
  auto at = [](Vec3 p, Vec3 q, Vec3 r)
  {
    const Vec3 u = q - p, v = r - p;
    return std::atan2(norm(cross(u, v)), dot(u, v));
  };
  return { at(a, b, c), at(b, c, a), at(c, a, b) };
}

// sigma_max / sigma_min of the linear map taking the surface triangle to the disk triangle.
double dilatation(Vec3 p0, Vec3 p1, Vec3 p2, Vec2 q0, Vec2 q1, Vec2 q2)
{
  // Surface triangle in an orthonormal frame of its plane.
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const double l1 = norm(e1);
  const Vec3 x = { e1.x / l1, e1.y / l1, e1.z / l1 };
  const Vec3 n = cross(e1, e2);
  Vec3 y = cross(n, x);
  const double ly = norm(y);
  y = { y.x / ly, y.y / ly, y.z / ly };
  const double s11 = dot(e1, x), s12 = dot(e2, x), s21 = dot(e1, y), s22 = dot(e2, y);
  const double sdet = s11 * s22 - s12 * s21;
  const Vec2 d1 = q1 - q0, d2 = q2 - q0;
  // J = D S^{-1}
  const double j11 = (d1.x * s22 - d2.x * s21) / sdet, j12 = (-d1.x * s12 + d2.x * s11) / sdet;
  const double j21 = (d1.y * s22 - d2.y * s21) / sdet, j22 = (-d1.y * s12 + d2.y * s11) / sdet;
  const double halfFrobenius2 = 0.5 * (j11 * j11 + j12 * j12 + j21 * j21 + j22 * j22);
  const double det = std::abs(j11 * j22 - j12 * j21);
  const double root = std::sqrt(std::max(0.0, (halfFrobenius2 - det) * (halfFrobenius2 + det)));
  const double sigmaMax2 = halfFrobenius2 + root;
  const double sigmaMin2 = det * det / std::max(sigmaMax2, TinyArea);
  return std::sqrt(sigmaMax2 / std::max(sigmaMin2, TinyArea));
}
} // namespace

DistortionFigures measureDistortion(const SurfaceMesh& surface, const std::vector<Vec2>& uv)
{
  DistortionFigures f;
  const size_t nt = surface.triangles.size();
  f.angleDistortion.resize(nt);
  f.dilatation.resize(nt);
  f.logAreaRatio.resize(nt);
  std::vector<double> diskArea(nt), surfaceArea(nt);
  double diskTotal = 0.0, surfaceTotal = 0.0;
  for (size_t t = 0; t < nt; ++t)
  {
    const auto& tri = surface.triangles[t];
    diskArea[t] = signedArea(uv[tri[0]], uv[tri[1]], uv[tri[2]]);
    surfaceArea[t] = triangleArea(surface, tri);
    diskTotal += diskArea[t];
    surfaceTotal += surfaceArea[t];
  }
  // The scorer's convention: the orientation with positive total area is the right one.
  const double orientation = diskTotal >= 0.0 ? 1.0 : -1.0;
  diskTotal = 0.0;
  for (size_t t = 0; t < nt; ++t)
  {
    diskArea[t] *= orientation;
    f.flippedTriangles += diskArea[t] <= 0.0;
    diskTotal += diskArea[t];
  }
  // The per-triangle figures (two sets of corner angles, logarithms, a 2x2 singular value
  // problem each) on both cores; the sums after, in triangle order, so that the figures do not
  // depend on the thread count.
  std::vector<std::array<double, 3>> degrees(nt);
  const std::int64_t count = static_cast<std::int64_t>(nt);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < count; ++t)
  {
    const auto& tri = surface.triangles[t];
    const Vec3 p0 = surface.points[tri[0]], p1 = surface.points[tri[1]],
               p2 = surface.points[tri[2]];
    const auto a3 = cornerAngles(p0, p1, p2);
    const auto a2 = cornerAngles(uv[tri[0]], uv[tri[1]], uv[tri[2]]);
    double logSum = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      degrees[t][k] = std::abs(a2[k] - a3[k]) * 180.0 / Pi;
      logSum += std::abs(std::log(std::max(a2[k], TinyArea) / a3[k]));
    }
    f.angleDistortion[t] = logSum / 3.0;
    const double weight = surfaceArea[t] / surfaceTotal;
    const double diskFraction = std::max(diskArea[t], TinyArea) / diskTotal;
    f.logAreaRatio[t] = std::log(diskFraction / weight);
    f.dilatation[t] = dilatation(p0, p1, p2, uv[tri[0]], uv[tri[1]], uv[tri[2]]);
  }
  double angleSum = 0.0;
  for (size_t t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      angleSum += degrees[t][k];
      f.maximumAngleDistortionDegrees = std::max(f.maximumAngleDistortionDegrees, degrees[t][k]);
    }
    const double weight = surfaceArea[t] / surfaceTotal;
    f.meanAbsLogAreaRatio += weight * std::abs(f.logAreaRatio[t]);
    f.maximumAbsLogAreaRatio = std::max(f.maximumAbsLogAreaRatio, std::abs(f.logAreaRatio[t]));
    f.meanDilatation += weight * f.dilatation[t];
    f.maximumDilatation = std::max(f.maximumDilatation, f.dilatation[t]);
  }
  f.meanAngleDistortionDegrees = nt ? angleSum / (3.0 * static_cast<double>(nt)) : 0.0;
  return f;
}

namespace
{
// Surface area (times `scale`) over image area per triangle and per point (the areas of the
// triangles around it); flipped or collapsed images get the largest finite ratio. The disk's
// and the sphere's AreaDensity.
void areaRatios(const SurfaceMesh& surface, const std::vector<double>& surfaceArea,
  const std::vector<double>& imageArea, double scale, std::vector<double>& perTriangle,
  std::vector<double>& perPoint)
{
  const size_t nt = surface.triangles.size();
  perTriangle.assign(nt, 0.0);
  perPoint.assign(surface.points.size(), 0.0);
  std::vector<double> pointImageArea(surface.points.size(), 0.0);
  double largest = 0.0;
  for (size_t t = 0; t < nt; ++t)
  {
    if (imageArea[t] > 0.0)
    {
      perTriangle[t] = scale * surfaceArea[t] / imageArea[t];
      largest = std::isfinite(perTriangle[t]) ? std::max(largest, perTriangle[t]) : largest;
    }
  }
  for (size_t t = 0; t < nt; ++t)
  {
    if (!(imageArea[t] > 0.0) || !std::isfinite(perTriangle[t]))
    {
      perTriangle[t] = largest;
    }
    for (int v : surface.triangles[t])
    {
      perPoint[v] += scale * surfaceArea[t];
      pointImageArea[v] += std::max(imageArea[t], 0.0);
    }
  }
  for (size_t v = 0; v < perPoint.size(); ++v)
  {
    perPoint[v] = pointImageArea[v] > 0.0 ? perPoint[v] / pointImageArea[v] : largest;
  }
}
} // namespace

void computeAreaDensity(const SurfaceMesh& surface, const std::vector<Vec2>& uv,
  std::vector<double>& perTriangle, std::vector<double>& perPoint)
{
  const size_t nt = surface.triangles.size();
  std::vector<double> surfaceArea(nt), diskArea(nt);
  double surfaceTotal = 0.0;
  for (size_t t = 0; t < nt; ++t)
  {
    const auto& tri = surface.triangles[t];
    surfaceArea[t] = triangleArea(surface, tri);
    diskArea[t] = signedArea(uv[tri[0]], uv[tri[1]], uv[tri[2]]);
    surfaceTotal += surfaceArea[t];
  }
  areaRatios(surface, surfaceArea, diskArea, Pi / surfaceTotal, perTriangle, perPoint);
}

namespace
{
// The chordal triangle abc in an orthonormal frame of its own plane (a at the origin, b on the
// x axis), so the planar dilatation applies; singular values do not see the frame.
std::array<Vec2, 3> inOwnPlane(Vec3 a, Vec3 b, Vec3 c)
{
  const Vec3 e1 = b - a, e2 = c - a;
  const double l1 = norm(e1);
  const Vec3 x = (1.0 / l1) * e1;
  Vec3 y = cross(cross(e1, e2), x);
  const double ly = norm(y);
  y = (1.0 / std::max(ly, TinyArea)) * y;
  return { Vec2{ 0.0, 0.0 }, Vec2{ l1, 0.0 }, Vec2{ dot(e2, x), dot(e2, y) } };
}

std::vector<Vec3> unitVectors(const std::vector<Vec3>& points)
{
  std::vector<Vec3> unit(points.size());
  for (size_t v = 0; v < points.size(); ++v)
  {
    unit[v] = normalized(points[v]);
  }
  return unit;
}
} // namespace

DistortionFigures measureSphereDistortion(
  const SurfaceMesh& surface, const std::vector<Vec3>& sphere)
{
  DistortionFigures f;
  const size_t nt = surface.triangles.size();
  f.angleDistortion.assign(nt, 0.0);
  f.dilatation.assign(nt, 1.0);
  f.logAreaRatio.assign(nt, 0.0);
  const std::vector<Vec3> unit = unitVectors(sphere);
  std::vector<double> surfaceArea(nt);
  double surfaceTotal = 0.0;
  for (size_t t = 0; t < nt; ++t)
  {
    surfaceArea[t] = triangleArea(surface, surface.triangles[t]);
    surfaceTotal += surfaceArea[t] > 0.0 ? surfaceArea[t] : 0.0;
  }
  // As the scorer: triangles of zero surface area are left out of every figure.
  double angleSum = 0.0;
  size_t corners = 0;
  for (size_t t = 0; t < nt; ++t)
  {
    if (!(surfaceArea[t] > 0.0))
    {
      continue;
    }
    const auto& tri = surface.triangles[t];
    const Vec3 a = unit[tri[0]], b = unit[tri[1]], c = unit[tri[2]];
    const double sphericalArea = sphericalTriangleArea(a, b, c);
    f.flippedTriangles += sphericalArea <= 0.0;
    const Vec3 p0 = surface.points[tri[0]], p1 = surface.points[tri[1]],
               p2 = surface.points[tri[2]];
    const auto a3 = cornerAngles(p0, p1, p2);
    const auto image = cornerAngles(a, b, c);
    double logSum = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const double degrees = std::abs(image[k] - a3[k]) * 180.0 / Pi;
      angleSum += degrees;
      f.maximumAngleDistortionDegrees = std::max(f.maximumAngleDistortionDegrees, degrees);
      logSum += std::abs(std::log(std::max(image[k], TinyArea) / a3[k]));
    }
    corners += 3;
    f.angleDistortion[t] = logSum / 3.0;

    const double weight = surfaceArea[t] / surfaceTotal;
    const double sphereFraction = std::max(sphericalArea, TinyArea) / (4.0 * Pi);
    f.logAreaRatio[t] = std::log(sphereFraction / weight);
    f.meanAbsLogAreaRatio += weight * std::abs(f.logAreaRatio[t]);
    f.maximumAbsLogAreaRatio = std::max(f.maximumAbsLogAreaRatio, std::abs(f.logAreaRatio[t]));

    const auto q = inOwnPlane(a, b, c);
    f.dilatation[t] = dilatation(p0, p1, p2, q[0], q[1], q[2]);
    f.meanDilatation += weight * f.dilatation[t];
    f.maximumDilatation = std::max(f.maximumDilatation, f.dilatation[t]);
  }
  f.meanAngleDistortionDegrees = corners ? angleSum / static_cast<double>(corners) : 0.0;
  return f;
}

void computeSphereAreaDensity(const SurfaceMesh& surface, const std::vector<Vec3>& sphere,
  std::vector<double>& perTriangle, std::vector<double>& perPoint)
{
  const size_t nt = surface.triangles.size();
  const std::vector<Vec3> unit = unitVectors(sphere);
  std::vector<double> surfaceArea(nt), sphericalArea(nt);
  double surfaceTotal = 0.0;
  for (size_t t = 0; t < nt; ++t)
  {
    const auto& tri = surface.triangles[t];
    surfaceArea[t] = triangleArea(surface, tri);
    sphericalArea[t] = sphericalTriangleArea(unit[tri[0]], unit[tri[1]], unit[tri[2]]);
    surfaceTotal += surfaceArea[t];
  }
  areaRatios(surface, surfaceArea, sphericalArea, 4.0 * Pi / surfaceTotal, perTriangle, perPoint);
}

//------------------------------------------------------------------------------
double rangeOf(const std::vector<double>& density)
{
  const auto range = std::minmax_element(density.begin(), density.end());
  return range.first == density.end() ? 1.0 : *range.second / *range.first;
}

//------------------------------------------------------------------------------
std::vector<double> densitiesAtAreaShares(
  const SurfaceMesh& surface, const std::vector<double>& density, const std::vector<double>& shares)
{
  std::vector<std::pair<double, double>> byDensity(density.size());
  double total = 0.0;
  for (size_t t = 0; t < density.size(); ++t)
  {
    byDensity[t] = { density[t], triangleArea(surface, surface.triangles[t]) };
    total += byDensity[t].second;
  }
  std::sort(byDensity.begin(), byDensity.end());
  std::vector<double> values;
  double below = 0.0;
  size_t next = 0;
  for (const double share : shares)
  {
    while (next + 1 < byDensity.size() && below + byDensity[next].second < share * total)
    {
      below += byDensity[next++].second;
    }
    values.push_back(byDensity.empty() ? 0.0 : byDensity[next].first);
  }
  return values;
}

//------------------------------------------------------------------------------
double crowdingRange(
  const SurfaceMesh& surface, const std::vector<double>& density, double lowShare)
{
  const double whole = rangeOf(density);
  if (whole <= CrowdedDensityRange)
  {
    return whole;
  }
  const double largest = *std::max_element(density.begin(), density.end());
  return largest / densitiesAtAreaShares(surface, density, { lowShare })[0];
}

} // namespace otparam
