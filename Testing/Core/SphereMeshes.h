// Closed test surfaces for the sphere's stages (sphere.md, "Exact checks"): points on the unit
// sphere crowded toward a pole by a Moebius dilation, their convex hull, and a surface of
// revolution with two waists.
#ifndef OTPARAM_TESTING_SPHEREMESHES_H
#define OTPARAM_TESTING_SPHEREMESHES_H

#include "Mesh/SurfaceMesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <cmath>
#include <map>
#include <tuple>

namespace otparam
{
namespace testing
{

// n points spread evenly over the unit sphere (the Fibonacci lattice; no point at a pole).
inline std::vector<Vec3> fibonacciSphere(int n)
{
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Vec3> points(n);
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(1.0 - z * z);
    points[i] = { r * std::cos(golden * i), r * std::sin(golden * i), z };
  }
  return points;
}

// The Moebius map of the sphere that scales the stereographic plane (projection from the north
// pole) by `factor`: factor > 1 pushes points toward the north pole.
inline Vec3 moebiusDilation(Vec3 p, double factor)
{
  const double u = factor * p.x / (1.0 - p.z), v = factor * p.y / (1.0 - p.z);
  const double s = u * u + v * v;
  return { 2.0 * u / (s + 1.0), 2.0 * v / (s + 1.0), (s - 1.0) / (s + 1.0) };
}

// The convex hull of points in convex position (each point a hull vertex), triangles
// counter-clockwise seen from outside, point i of the mesh = points[i].
inline SurfaceMesh convexHullMesh(const std::vector<Vec3>& points)
{
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  std::vector<Kernel::Point_3> cgalPoints;
  std::map<std::tuple<double, double, double>, int> index;
  for (size_t i = 0; i < points.size(); ++i)
  {
    cgalPoints.emplace_back(points[i].x, points[i].y, points[i].z);
    index[{ points[i].x, points[i].y, points[i].z }] = static_cast<int>(i);
  }
  Mesh hull;
  CGAL::convex_hull_3(cgalPoints.begin(), cgalPoints.end(), hull);
  SurfaceMesh mesh;
  mesh.points = points;
  for (auto f : hull.faces())
  {
    Triangle t{};
    int k = 0;
    for (auto v : hull.vertices_around_face(hull.halfedge(f)))
    {
      const auto& p = hull.point(v);
      t[k++] = index.at({ p.x(), p.y(), p.z() });
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

// The radius of the two-waisted surface of revolution of sphere.md's exact check.
inline double twoWaistRadius(double z)
{
  return std::sqrt(std::max(0.0, 1.0 - z * z)) * (0.7 + 0.3 * std::cos(2.0 * M_PI * z));
}

// The surface of revolution r(z) about the z axis, z in [-1, 1]: `rings` rings of `sectors`
// points between the two poles (point 0 the north pole z = 1, the last point the south pole),
// rings evenly spaced in the polar angle of the unit sphere, triangles outward.
template <typename Radius>
SurfaceMesh revolutionSurface(Radius radius, int rings, int sectors)
{
  SurfaceMesh mesh;
  mesh.points.push_back({ 0.0, 0.0, 1.0 });
  for (int r = 1; r <= rings; ++r)
  {
    const double z = std::cos(M_PI * r / (rings + 1));
    for (int s = 0; s < sectors; ++s)
    {
      // Alternate rings are turned by half a sector so the triangles stay well shaped.
      const double phi = 2.0 * M_PI * (s + 0.5 * (r % 2)) / sectors;
      mesh.points.push_back({ radius(z) * std::cos(phi), radius(z) * std::sin(phi), z });
    }
  }
  mesh.points.push_back({ 0.0, 0.0, -1.0 });
  const int south = static_cast<int>(mesh.points.size()) - 1;
  auto at = [sectors](int r, int s) { return 1 + (r - 1) * sectors + (s % sectors); };
  for (int s = 0; s < sectors; ++s)
  {
    mesh.triangles.push_back({ 0, at(1, s), at(1, s + 1) });
    mesh.triangles.push_back({ south, at(rings, s + 1), at(rings, s) });
  }
  for (int r = 1; r < rings; ++r)
  {
    for (int s = 0; s < sectors; ++s)
    {
      // Odd rings are shifted forward: connect each quad along its shorter diagonal.
      const int a = at(r, s), b = at(r, s + 1), c = at(r + 1, s), d = at(r + 1, s + 1);
      if (r % 2)
      {
        mesh.triangles.push_back({ a, d, b });
        mesh.triangles.push_back({ a, c, d });
      }
      else
      {
        mesh.triangles.push_back({ a, c, b });
        mesh.triangles.push_back({ b, c, d });
      }
    }
  }
  return mesh;
}

// A square pyramid: an n x n grid of unit squares (each cut by a diagonal, alternating) as its
// base and one apex `height` above the base's centre, joined to every base boundary point by
// a fan of thin triangles. Its base corners are sharp (three triangles each, the cotangent
// weight toward the apex negative), as on meshes of boxes and on VTK's coarse sources.
inline SurfaceMesh pyramidMesh(int n, double height)
{
  SurfaceMesh mesh;
  auto id = [n](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i <= n; ++i)
  {
    for (int j = 0; j <= n; ++j)
    {
      mesh.points.push_back({ static_cast<double>(i), static_cast<double>(j), 0.0 });
    }
  }
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2)
      {
        mesh.triangles.push_back({ a, c, b });
        mesh.triangles.push_back({ a, d, c });
      }
      else
      {
        mesh.triangles.push_back({ a, d, b });
        mesh.triangles.push_back({ b, d, c });
      }
    }
  }
  std::vector<int> rim; // counter-clockwise seen from above
  for (int i = 0; i < n; ++i)
  {
    rim.push_back(id(i, 0));
  }
  for (int j = 0; j < n; ++j)
  {
    rim.push_back(id(n, j));
  }
  for (int i = n; i > 0; --i)
  {
    rim.push_back(id(i, n));
  }
  for (int j = n; j > 0; --j)
  {
    rim.push_back(id(0, j));
  }
  const int apex = static_cast<int>(mesh.points.size());
  mesh.points.push_back({ 0.5 * n, 0.5 * n, height });
  for (size_t k = 0; k < rim.size(); ++k)
  {
    mesh.triangles.push_back({ rim[k], rim[(k + 1) % rim.size()], apex });
  }
  return mesh;
}

} // namespace testing
} // namespace otparam

#endif
