#include "Sampling/SphericalDensityField.h"

#include "Common/SphericalGeometry.h"
#include "Sampling/Sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>

namespace otparam
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
} // namespace

//------------------------------------------------------------------------------
std::unique_ptr<SphericalDensityField> SphericalDensityField::create(
  const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
  const std::vector<double>& perTriangle, std::string& error)
{
  std::unique_ptr<SphericalDensityField> field(new SphericalDensityField);
  field->Points = points;
  field->Triangles = triangles;
  field->PerTriangle = relativeDensity(perTriangle); // non-finite and non-positive values kept
  error = field->checkAndBuild();
  if (!error.empty())
  {
    return nullptr;
  }
  return field;
}

//------------------------------------------------------------------------------
namespace
{
using EdgeMap = std::unordered_map<long long, std::pair<int, int>>; // (from, to) -> (triangle, k)

std::string checkPointsOnSphere(std::vector<Vec3>& points)
{
  for (size_t i = 0; i < points.size(); ++i)
  {
    const double r = norm(points[i]);
    if (!std::isfinite(r) || std::abs(r - 1.0) > 1e-9)
    {
      std::ostringstream msg;
      msg << "Point " << i << " of the spherical density is not on the unit sphere (|p| = " << r
          << ").";
      return msg.str();
    }
    // Unit vectors as `normalized` leaves them are kept to the bit: a crowded map's tiny
    // triangles, checked positive by their maker (healSphereFolds), could flip when rounded again.
    if (std::abs(r - 1.0) > 4.0 * std::numeric_limits<double>::epsilon())
    {
      points[i] = normalized(points[i]);
    }
  }
  return {};
}

std::string checkTriangles(
  const std::vector<Triangle>& triangles, const std::vector<double>& perTriangle, size_t n)
{
  std::ostringstream msg;
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    const double g = perTriangle[t];
    if (!std::isfinite(g) || !(g > 0.0))
    {
      msg << "The density of triangle " << t << " must be positive and finite; got " << g << ".";
      return msg.str();
    }
    const Triangle& tri = triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] < 0 || static_cast<size_t>(tri[k]) >= n || tri[k] == tri[(k + 1) % 3])
      {
        msg << "Triangle " << t << " has an invalid or repeated point id.";
        return msg.str();
      }
    }
  }
  return {};
}

long long edgeKey(size_t n, int a, int b)
{
  return static_cast<long long>(a) * static_cast<long long>(n) + b;
}

// Each directed edge once (its reverse is looked up by the caller): a closed, consistently
// oriented surface.
std::string directedEdges(const std::vector<Triangle>& triangles, size_t n, EdgeMap& edges)
{
  edges.reserve(3 * triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Triangle& tri = triangles[t];
      const int a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
      if (!edges.emplace(edgeKey(n, a, b), std::make_pair(int(t), k)).second)
      {
        std::ostringstream msg;
        msg << "Edge " << a << "-" << b << " of triangle " << t
            << " is used twice in the same direction: the density mesh is not a consistently "
               "oriented closed surface.";
        return msg.str();
      }
    }
  }
  return {};
}
} // namespace

//------------------------------------------------------------------------------
std::string SphericalDensityField::checkAndBuild()
{
  const size_t n = this->Points.size(), m = this->Triangles.size();
  if (m < 4 || this->PerTriangle.size() != m)
  {
    std::ostringstream msg;
    msg << "The spherical density needs a closed mesh of at least 4 triangles and one density "
           "value per triangle; got "
        << m << " triangles and " << this->PerTriangle.size() << " values.";
    return msg.str();
  }
  EdgeMap edges;
  std::string error = checkPointsOnSphere(this->Points);
  error = error.empty() ? checkTriangles(this->Triangles, this->PerTriangle, n) : error;
  error = error.empty() ? directedEdges(this->Triangles, n, edges) : error;
  error = error.empty() ? this->buildNeighboursAndAreas(edges) : error;
  if (error.empty())
  {
    this->buildStartTable();
  }
  return error;
}

//------------------------------------------------------------------------------
// Each edge's neighbour across it and great-circle normal, each triangle's spherical area, the
// density's integral; what is wrong when the triangles do not tile the sphere.
std::string SphericalDensityField::buildNeighboursAndAreas(const EdgeMap& edges)
{
  std::ostringstream msg;
  const size_t n = this->Points.size(), m = this->Triangles.size();
  this->Neighbor.assign(m, { -1, -1, -1 });
  this->EdgeNormal.resize(m);
  this->Area.resize(m);
  this->Moment.resize(m);
  double area = 0.0;
  this->Integral = 0.0;
  for (size_t t = 0; t < m; ++t)
  {
    const Triangle& tri = this->Triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      const int a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
      const auto it = edges.find(edgeKey(n, b, a));
      if (it == edges.end())
      {
        msg << "Edge " << a << "-" << b << " of triangle " << t
            << " has no triangle on its other side: the density mesh is not closed.";
        return msg.str();
      }
      this->Neighbor[t][k] = it->second.first;
      this->EdgeNormal[t][k] = cross(this->Points[a], this->Points[b]);
    }
    const Vec3 &a = this->Points[tri[0]], &b = this->Points[tri[1]], &c = this->Points[tri[2]];
    this->Area[t] = sphericalTriangleArea(a, b, c);
    if (!(this->Area[t] > 0.0))
    {
      msg << "Triangle " << t
          << " of the spherical density is degenerate or clockwise seen from outside.";
      return msg.str();
    }
    this->Moment[t] = sphericalPolygonMoment({ a, b, c });
    area += this->Area[t];
    this->Integral += this->Area[t] * this->PerTriangle[t];
  }
  if (std::abs(area - 4.0 * Pi) > 1e-9 * 4.0 * Pi)
  {
    msg << "The triangles of the spherical density cover an area of " << area
        << " instead of 4 pi: they overlap or leave gaps.";
    return msg.str();
  }
  return {};
}

//------------------------------------------------------------------------------
bool SphericalDensityField::contains(int t, Vec3 x) const
{
  const auto& e = this->EdgeNormal[t];
  return dot(e[0], x) >= 0.0 && dot(e[1], x) >= 0.0 && dot(e[2], x) >= 0.0;
}

//------------------------------------------------------------------------------
// Visibility walk: cross an edge that x lies outside of, starting the search at a rotating
// edge (a fixed order can cycle on a non-Delaunay mesh). Returns -1 after maximumSteps.
int SphericalDensityField::walk(Vec3 x, int t, int maximumSteps) const
{
  for (int step = 0; step < maximumSteps; ++step)
  {
    const auto& e = this->EdgeNormal[t];
    int across = -1;
    for (int j = 0; j < 3; ++j)
    {
      const int k = (j + step) % 3;
      if (dot(e[k], x) < 0.0)
      {
        across = k;
        break;
      }
    }
    if (across < 0)
    {
      return t;
    }
    t = this->Neighbor[t][across];
  }
  return -1;
}

//------------------------------------------------------------------------------
int SphericalDensityField::tableCell(Vec3 x) const
{
  const double ax = std::abs(x.x), ay = std::abs(x.y), az = std::abs(x.z);
  int face;
  double u, v, w;
  if (ax >= ay && ax >= az)
  {
    face = x.x > 0 ? 0 : 1, u = x.y, v = x.z, w = ax;
  }
  else if (ay >= az)
  {
    face = x.y > 0 ? 2 : 3, u = x.z, v = x.x, w = ay;
  }
  else
  {
    face = x.z > 0 ? 4 : 5, u = x.x, v = x.y, w = az;
  }
  const int s = this->TableSize;
  const auto cell = [s, w](double c)
  { return std::clamp(static_cast<int>((c / w + 1.0) * 0.5 * s), 0, s - 1); };
  return (face * s + cell(u)) * s + cell(v);
}

//------------------------------------------------------------------------------
// One starting triangle per cube-map cell (about 4 triangles per cell), each found by a short
// walk from the previous cell's.
void SphericalDensityField::buildStartTable()
{
  const int m = static_cast<int>(this->Triangles.size());
  this->TableSize = std::clamp(static_cast<int>(std::ceil(std::sqrt(m / 24.0))), 1, 256);
  const int s = this->TableSize;
  this->StartTable.assign(6 * s * s, 0);
  int previous = 0;
  for (int face = 0; face < 6; ++face)
  {
    for (int i = 0; i < s; ++i)
    {
      for (int j = 0; j < s; ++j)
      {
        const double u = 2.0 * (i + 0.5) / s - 1.0, v = 2.0 * (j + 0.5) / s - 1.0;
        const double sign = face % 2 == 0 ? 1.0 : -1.0;
        Vec3 x;
        switch (face / 2)
        {
          case 0:
            x = { sign, u, v };
            break;
          case 1:
            x = { v, sign, u };
            break;
          default:
            x = { u, v, sign };
            break;
        }
        x = normalized(x);
        this->StartTable[tableCell(x)] = 0; // placeholder so locate falls back to a scan
        int t = walk(x, previous, 4 * m + 16);
        if (t < 0)
        {
          t = locate(x, previous);
        }
        this->StartTable[tableCell(x)] = previous = t;
      }
    }
  }
}

//------------------------------------------------------------------------------
int SphericalDensityField::locate(Vec3 x, int hint) const
{
  const int m = static_cast<int>(this->Triangles.size());
  const int start = hint >= 0 && hint < m ? hint : this->StartTable[tableCell(x)];
  const int maximumSteps = 64 + 8 * static_cast<int>(std::sqrt(static_cast<double>(m)));
  int t = walk(x, start, maximumSteps);
  if (t < 0 && hint >= 0)
  {
    t = walk(x, this->StartTable[tableCell(x)], maximumSteps);
  }
  if (t >= 0)
  {
    return t;
  }
  // The walk cycled (a very irregular mesh) or x sits in a rounding gap at a vertex: the
  // triangle that x is least outside of.
  int best = 0;
  double bestSide = -std::numeric_limits<double>::infinity();
  for (int u = 0; u < m; ++u)
  {
    const auto& e = this->EdgeNormal[u];
    const double side = std::min({ dot(e[0], x), dot(e[1], x), dot(e[2], x) });
    if (side > bestSide && dot(this->Points[this->Triangles[u][0]], x) > 0.0)
    {
      bestSide = side;
      best = u;
    }
  }
  return best;
}

//------------------------------------------------------------------------------
// The polygon clipped by triangle t's edges (0, 1), (1, 2), (2, 0) in that order, as
// intersectSphericalPolygons does, into scratch.piece; an edge with the whole piece inside
// leaves it as it is and is skipped (no copy). False when nothing is left.
bool SphericalDensityField::clipToTriangle(
  int t, const std::vector<Vec3>& polygon, Scratch& scratch) const
{
  scratch.piece.assign(polygon.begin(), polygon.end());
  for (const int k : { 2, 0, 1 }) // EdgeNormal[t][k] is the edge opposite corner k
  {
    const Vec3 normal = this->EdgeNormal[t][k];
    if (std::all_of(scratch.piece.begin(), scratch.piece.end(),
          [&](const Vec3& v) { return dot(normal, v) >= 0.0; }))
    {
      continue;
    }
    clipByGreatCircle(scratch.piece, normal, scratch.clipped);
    scratch.piece.swap(scratch.clipped);
    if (scratch.piece.size() < 3)
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void SphericalDensityField::integrate(const std::vector<Vec3>& polygon, Vec3 inside, int& hint,
  double power, Scratch& scratch, double& mass, Vec3* moment, double* gMass, double* area) const
{
  mass = 0.0;
  if (gMass)
  {
    *gMass = 0.0;
  }
  if (area)
  {
    *area = 0.0;
  }
  if (moment)
  {
    *moment = Vec3{};
  }
  hint = locate(inside, hint);
  if (scratch.stamp.size() != this->Triangles.size())
  {
    scratch.stamp.assign(this->Triangles.size(), 0);
    scratch.current = 0;
  }
  const int stamp = ++scratch.current;
  scratch.polygonNormals.resize(polygon.size());
  for (size_t k = 0; k < polygon.size(); ++k)
  {
    scratch.polygonNormals[k] = cross(polygon[k], polygon[(k + 1) % polygon.size()]);
  }
  scratch.stack.clear();
  scratch.stack.push_back(hint);
  scratch.stamp[hint] = stamp;
  // Flood the triangles that overlap the polygon: the polygon is convex, so those overlapping
  // it in a positive area are connected across edges.
  while (!scratch.stack.empty())
  {
    const int t = scratch.stack.back();
    scratch.stack.pop_back();
    const Triangle& tri = this->Triangles[t];
    // Most triangles of the flood's rim only touch the polygon's neighbourhood: when every
    // corner of the polygon is outside one of the triangle's edges there is no overlap.
    bool separated = false;
    for (int k = 0; k < 3 && !separated; ++k)
    {
      separated = std::all_of(polygon.begin(), polygon.end(),
        [&](const Vec3& v) { return dot(this->EdgeNormal[t][k], v) < 0.0; });
    }
    if (separated)
    {
      continue;
    }
    // A triangle inside every edge of the polygon is whole: its area and moment are kept (most
    // of a fine mesh's triangles; the clipping, areas and moments were 60% of the sphere's
    // sampler at 194k points).
    const bool whole = std::all_of(scratch.polygonNormals.begin(), scratch.polygonNormals.end(),
      [&](const Vec3& normal)
      {
        return dot(normal, this->Points[tri[0]]) >= 0.0 &&
          dot(normal, this->Points[tri[1]]) >= 0.0 && dot(normal, this->Points[tri[2]]) >= 0.0;
      });
    std::vector<Vec3>& piece = scratch.piece;
    if (!whole && !this->clipToTriangle(t, polygon, scratch))
    {
      continue;
    }
    const double g = power == 1.0 ? this->PerTriangle[t] : std::pow(this->PerTriangle[t], power);
    const double pieceArea = whole ? this->Area[t] : sphericalPolygonArea(piece);
    mass += g * pieceArea;
    if (gMass)
    {
      *gMass += this->PerTriangle[t] * pieceArea;
    }
    if (area)
    {
      *area += pieceArea;
    }
    if (moment)
    {
      *moment = *moment + g * (whole ? this->Moment[t] : sphericalPolygonMoment(piece));
    }
    for (int k = 0; k < 3; ++k)
    {
      const int u = this->Neighbor[t][k];
      if (scratch.stamp[u] != stamp)
      {
        scratch.stamp[u] = stamp;
        scratch.stack.push_back(u);
      }
    }
  }
}

} // namespace otparam
