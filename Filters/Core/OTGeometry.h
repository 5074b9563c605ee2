// Plain 2D geometry shared by the OTParam core (no VTK, no CGAL in this header).
#ifndef OTPARAM_OTGEOMETRY_H
#define OTPARAM_OTGEOMETRY_H

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

using Triangle = std::array<int, 3>;

} // namespace otparam

#endif
