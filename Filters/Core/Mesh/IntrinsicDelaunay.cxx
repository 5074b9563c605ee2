#include "Mesh/IntrinsicDelaunay.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace otparam
{
namespace
{
// The area of a triangle from its edge lengths, by Kahan's stable form of Heron's formula (0 for
// lengths that violate the triangle inequality by rounding).
double areaFromLengths(const std::array<double, 3>& l)
{
  double x = l[0], y = l[1], z = l[2];
  if (x < y)
    std::swap(x, y);
  if (x < z)
    std::swap(x, z);
  if (y < z)
    std::swap(y, z);
  const double product = (x + (y + z)) * (z - (x - y)) * (z + (x - y)) * (x + (y - z));
  return product > 0.0 ? 0.25 * std::sqrt(product) : 0.0;
}

// The angle at corner k.
double cornerAngle(const std::array<double, 3>& l, int k)
{
  const double a = l[k], b = l[(k + 1) % 3], c = l[(k + 2) % 3];
  return std::atan2(4.0 * areaFromLengths(l), b * b + c * c - a * a);
}
} // namespace

double halfCotangent(const std::array<double, 3>& l, int k)
{
  const double a = l[k], b = l[(k + 1) % 3], c = l[(k + 2) % 3];
  return (b * b + c * c - a * a) / (8.0 * areaFromLengths(l));
}

namespace
{
// Halfedge 3 t + k runs from corner k + 1 to corner k + 2 of triangle t (opposite corner k);
// twin[h] is the halfedge the other way along the same edge, -1 on the boundary.
std::vector<std::int64_t> twinHalfedges(const std::vector<Triangle>& T)
{
  const size_t halfedges = 3 * T.size();
  std::vector<std::int64_t> twin(halfedges, -1);
  std::unordered_map<std::uint64_t, std::int64_t> byEnds;
  byEnds.reserve(halfedges);
  auto key = [](int from, int to)
  {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) |
      static_cast<std::uint32_t>(to);
  };
  for (size_t h = 0; h < halfedges; ++h)
  {
    const Triangle& t = T[h / 3];
    const int k = static_cast<int>(h % 3);
    byEnds[key(t[(k + 1) % 3], t[(k + 2) % 3])] = static_cast<std::int64_t>(h);
  }
  for (size_t h = 0; h < halfedges; ++h)
  {
    const Triangle& t = T[h / 3];
    const int k = static_cast<int>(h % 3);
    const auto found = byEnds.find(key(t[(k + 2) % 3], t[(k + 1) % 3]));
    if (found != byEnds.end())
    {
      twin[h] = found->second;
    }
  }
  return twin;
}

// The intrinsic flip of the interior edge under halfedge h, when it is not locally Delaunay:
// the two triangles become (a, o2, o1) and (o2, b, o1), the new edge's length from unfolding
// them at a. Returns false (nothing changed) for a Delaunay edge or a degenerate pair.
bool flipIfNotDelaunay(std::int64_t h, std::vector<Triangle>& T,
  std::vector<std::array<double, 3>>& L, std::vector<std::int64_t>& twin)
{
  const std::int64_t g = twin[h];
  if (g < 0)
  {
    return false;
  }
  const std::int64_t t1 = h / 3, t2 = g / 3;
  const int k1 = static_cast<int>(h % 3), k2 = static_cast<int>(g % 3);
  const double cotangents = halfCotangent(L[t1], k1) + halfCotangent(L[t2], k2);
  if (!(cotangents < -1e-12 * std::abs(halfCotangent(L[t1], k1))) || t1 == t2)
  {
    return false; // locally Delaunay (up to rounding)
  }
  const int o1 = T[t1][k1], a = T[t1][(k1 + 1) % 3], b = T[t1][(k1 + 2) % 3];
  const int o2 = T[t2][k2];
  if (o1 == o2)
  {
    return false;
  }
  const std::int64_t o1a = 3 * t1 + (k1 + 2) % 3, bo1 = 3 * t1 + (k1 + 1) % 3;
  const std::int64_t o2b = 3 * t2 + (k2 + 2) % 3, ao2 = 3 * t2 + (k2 + 1) % 3;
  const double lengthO1A = L[t1][(k1 + 2) % 3], lengthBO1 = L[t1][(k1 + 1) % 3];
  const double lengthO2B = L[t2][(k2 + 2) % 3], lengthAO2 = L[t2][(k2 + 1) % 3];
  // Unfold the two triangles at a: the new edge o1-o2 spans both angles there.
  const double angle = cornerAngle(L[t1], (k1 + 1) % 3) + cornerAngle(L[t2], (k2 + 2) % 3);
  const double newLength = std::sqrt(std::max(0.0,
    lengthO1A * lengthO1A + lengthAO2 * lengthAO2 - 2.0 * lengthO1A * lengthAO2 * std::cos(angle)));
  const std::int64_t twinO1A = twin[o1a], twinBO1 = twin[bo1], twinO2B = twin[o2b],
                     twinAO2 = twin[ao2];
  T[t1] = { a, o2, o1 };
  L[t1] = { newLength, lengthO1A, lengthAO2 };
  T[t2] = { o2, b, o1 };
  L[t2] = { lengthBO1, newLength, lengthO2B };
  auto link = [&](std::int64_t x, std::int64_t y)
  {
    twin[x] = y;
    if (y >= 0)
    {
      twin[y] = x;
    }
  };
  link(3 * t1 + 0, 3 * t2 + 1);
  link(3 * t1 + 1, twinO1A);
  link(3 * t1 + 2, twinAO2);
  link(3 * t2 + 0, twinBO1);
  link(3 * t2 + 2, twinO2B);
  return true;
}
} // namespace

IntrinsicTriangulation intrinsicDelaunay(
  const std::vector<Triangle>& triangles, const std::vector<std::array<double, 3>>& lengths)
{
  IntrinsicTriangulation result{ triangles, lengths, 0 };
  std::vector<Triangle>& T = result.triangles;
  const size_t halfedges = 3 * T.size();
  std::vector<std::int64_t> twin = twinHalfedges(T);
  std::vector<std::int64_t> queue;
  std::vector<char> queued(halfedges, 0);
  auto push = [&](std::int64_t h)
  {
    if (h >= 0 && twin[h] >= 0 && !queued[h] && !queued[twin[h]])
    {
      queued[h] = 1;
      queue.push_back(h);
    }
  };
  for (size_t h = 0; h < halfedges; ++h)
  {
    push(static_cast<std::int64_t>(h));
  }
  // Each flip strictly lowers the Dirichlet energy of every function (Rippa), so the loop ends;
  // the cap only guards against rounding ping-pong on nearly cocircular quads.
  const std::int64_t maximumFlips = 100 * static_cast<std::int64_t>(halfedges) + 1000;
  while (!queue.empty() && result.flips < maximumFlips)
  {
    const std::int64_t h = queue.back();
    queue.pop_back();
    queued[h] = 0;
    const std::int64_t t1 = h / 3, t2 = twin[h] / 3;
    if (!flipIfNotDelaunay(h, T, result.lengths, twin))
    {
      continue;
    }
    ++result.flips;
    for (std::int64_t e : { 3 * t1 + 1, 3 * t1 + 2, 3 * t2 + 0, 3 * t2 + 2 })
    {
      push(e);
    }
  }
  return result;
}

//------------------------------------------------------------------------------
std::vector<std::array<double, 3>> edgeLengthsOf(
  const std::vector<Vec3>& points, const std::vector<Triangle>& triangles)
{
  std::vector<std::array<double, 3>> lengths(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    const Triangle& tri = triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      lengths[t][k] = norm(points[tri[(k + 2) % 3]] - points[tri[(k + 1) % 3]]);
    }
  }
  return lengths;
}

} // namespace otparam
