// Geometry on the unit sphere shared by the sphere's stages (sphere.md): spherical triangles and
// convex spherical polygons bounded by great-circle arcs, given by their unit vertex vectors in
// counter-clockwise order seen from outside.
#ifndef OTPARAM_COMMON_SPHERICALGEOMETRY_H
#define OTPARAM_COMMON_SPHERICALGEOMETRY_H

#include "Common/Geometry.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace otparam
{

// atan2(y, x) for x > 0, by atan's series where |y| <= 1e-3 x (the first omitted term is below
// 2e-19 of the result): the small triangles and arcs of fine meshes, whose atan2 calls were a
// fifth of the sphere's composition and sampler at 194k points.
inline double atan2Small(double y, double x)
{
  if (x > 0.0 && std::abs(y) <= 1e-3 * x)
  {
    const double t = y / x, t2 = t * t;
    return t * (1.0 - t2 * (1.0 / 3.0 - 0.2 * t2));
  }
  return std::atan2(y, x);
}

// An orthonormal basis (e1, e2) of the tangent plane at the unit vector p, with (e1, e2, p)
// right-handed: a chart there sees counterclockwise what is counterclockwise from outside.
inline void tangentFrame(Vec3 p, Vec3& e1, Vec3& e2)
{
  const Vec3 helper = std::abs(p.x) < 0.6 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
  e1 = normalized(cross(p, helper));
  e2 = cross(p, e1);
}

// Signed area of the spherical triangle abc (positive when counter-clockwise seen from
// outside), by Eriksson's formula tan(E / 2) = a.(b x c) / (1 + a.b + b.c + c.a). The triple
// product is taken of differences, a.((b - a) x (c - a)), which keeps its relative precision
// for tiny triangles.
inline double sphericalTriangleArea(Vec3 a, Vec3 b, Vec3 c)
{
  const double triple = dot(a, cross(b - a, c - a));
  return 2.0 * atan2Small(triple, 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
}

// Lambert's azimuthal equal-area projection, inverted: the unit disk onto the cap around the
// north pole that holds `capShare` of the sphere's area, area-preservingly up to that factor
// (the disk's centre to the pole, its circle to the cap's rim). x and y keep the relative
// precision of w near the centre.
inline Vec3 liftDiskToCap(Vec2 w, double capShare)
{
  const double r2 = w.x * w.x + w.y * w.y;
  const double scale = 2.0 * std::sqrt(capShare * std::max(0.0, 1.0 - capShare * r2));
  return { scale * w.x, scale * w.y, 1.0 - 2.0 * capShare * r2 };
}

// Area of a convex spherical polygon (fan from its first vertex).
inline double sphericalPolygonArea(const std::vector<Vec3>& polygon)
{
  double area = 0.0;
  for (size_t k = 1; k + 1 < polygon.size(); ++k)
  {
    area += sphericalTriangleArea(polygon[0], polygon[k], polygon[k + 1]);
  }
  return area;
}

// Angle between unit vectors, accurate for small angles too.
inline double sphericalDistance(Vec3 a, Vec3 b)
{
  return atan2Small(norm(cross(a, b)), dot(a, b));
}

// The integral of x dA over a convex spherical polygon (its centroid, unnormalized): the
// region and the planar sectors joining its edges to the origin close a surface over which the
// normal integrates to 0, so it is sum over edges of (angle / 2) times the edge's plane normal
// pointing inside.
inline Vec3 sphericalPolygonMoment(const std::vector<Vec3>& polygon)
{
  Vec3 moment;
  for (size_t k = 0; k < polygon.size(); ++k)
  {
    const Vec3 a = polygon[k], b = polygon[(k + 1) % polygon.size()];
    const Vec3 normal = cross(a, b);
    const double length = norm(normal);
    if (length > 0.0)
    {
      moment = moment + (0.5 * sphericalDistance(a, b) / length) * normal;
    }
  }
  return moment;
}

// The part of a convex spherical polygon where dot(normal, x) >= 0 (Sutherland-Hodgman with
// great-circle arcs: an arc crosses the plane at the normalized positive combination of its
// ends, which stays on the arc).
inline void clipByGreatCircle(const std::vector<Vec3>& polygon, Vec3 normal, std::vector<Vec3>& out)
{
  out.clear();
  const size_t n = polygon.size();
  for (size_t k = 0; k < n; ++k)
  {
    const Vec3 a = polygon[k], b = polygon[(k + 1) % n];
    const double da = dot(normal, a), db = dot(normal, b);
    if (da >= 0.0)
    {
      out.push_back(a);
    }
    if ((da >= 0.0) != (db >= 0.0))
    {
      const double t = da / (da - db);
      out.push_back(normalized((1.0 - t) * a + t * b));
    }
  }
}

inline std::vector<Vec3> clipByGreatCircle(const std::vector<Vec3>& polygon, Vec3 normal)
{
  std::vector<Vec3> out;
  clipByGreatCircle(polygon, normal, out);
  return out;
}

// The intersection of two convex spherical polygons (each within a hemisphere).
inline std::vector<Vec3> intersectSphericalPolygons(
  std::vector<Vec3> subject, const std::vector<Vec3>& clip)
{
  for (size_t k = 0; k < clip.size() && subject.size() >= 3; ++k)
  {
    subject = clipByGreatCircle(subject, cross(clip[k], clip[(k + 1) % clip.size()]));
  }
  return subject.size() >= 3 ? subject : std::vector<Vec3>{};
}

} // namespace otparam

#endif
