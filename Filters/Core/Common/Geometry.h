// Plain 2D and 3D geometry shared by the OTParam core (no VTK, no CGAL in this header).
#ifndef OTPARAM_COMMON_GEOMETRY_H
#define OTPARAM_COMMON_GEOMETRY_H

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace otparam
{

struct Vec2
{
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b)
{
  return { a.x + b.x, a.y + b.y };
}
inline Vec2 operator-(Vec2 a, Vec2 b)
{
  return { a.x - b.x, a.y - b.y };
}
inline Vec2 operator*(double s, Vec2 a)
{
  return { s * a.x, s * a.y };
}
inline double dot(Vec2 a, Vec2 b)
{
  return a.x * b.x + a.y * b.y;
}
inline double cross(Vec2 a, Vec2 b)
{
  return a.x * b.y - a.y * b.x;
}
inline double norm(Vec2 a)
{
  return std::hypot(a.x, a.y);
}
// Whether x lies to the right of the line from p to q by more than rounding: by more than
// 1e-12 of the cross product's terms.
inline bool rightOfBeyondRounding(Vec2 p, Vec2 q, Vec2 x)
{
  const Vec2 d = q - p, r = x - p;
  return cross(d, r) < -1e-12 * (std::abs(d.x) + std::abs(d.y)) * (std::abs(r.x) + std::abs(r.y));
}
// The point of segment ab nearest to x (a and b distinct).
inline Vec2 closestOnSegment(Vec2 x, Vec2 a, Vec2 b)
{
  const Vec2 d = b - a;
  const double t = std::clamp(dot(x - a, d) / dot(d, d), 0.0, 1.0);
  return a + t * d;
}

struct Vec3
{
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

inline Vec3 operator-(Vec3 a, Vec3 b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}
inline Vec3 operator+(Vec3 a, Vec3 b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}
inline Vec3 operator*(double s, Vec3 a)
{
  return { s * a.x, s * a.y, s * a.z };
}
inline double dot(Vec3 a, Vec3 b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(Vec3 a, Vec3 b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
inline double norm(Vec3 a)
{
  return std::sqrt(dot(a, a));
}
inline Vec3 normalized(Vec3 a)
{
  return (1.0 / norm(a)) * a;
}

using Triangle = std::array<int, 3>;

} // namespace otparam

#endif
