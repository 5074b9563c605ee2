// Step 2 of the composition (DiskComposition.h): flipped triangles untangled. Private to the
// composition stage.
#ifndef OTPARAM_COMPOSITION_UNTANGLING_H
#define OTPARAM_COMPOSITION_UNTANGLING_H

#include "Composition/Composition.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <limits>

namespace otparam
{
namespace composition
{

// The point p that maximizes min_k area(p, b_k, c_k) over a star's rim edges (b_k, c_k):
// each area is linear in p, so this is a linear program in (p, t) whose optimum has three
// active constraints, found by trying every triple (stars are small). `start` is kept unless
// some point does better.
inline Vec2 maximizeSmallestArea(const std::vector<std::pair<Vec2, Vec2>>& rim, Vec2 start)
{
  auto smallest = [&rim](Vec2 p)
  {
    double value = HUGE_VAL;
    for (const auto& edge : rim)
    {
      value = std::min(value, signedArea(p, edge.first, edge.second));
    }
    return value;
  };
  struct Plane
  {
    double gx, gy, c; // area(p) = gx * p.x + gy * p.y + c
  };
  std::vector<Plane> planes;
  for (const auto& edge : rim)
  {
    const Vec2 b = edge.first, c = edge.second;
    // area = (cross(b, c) + cross(p, b - c)) / 2
    planes.push_back({ 0.5 * (b.y - c.y), -0.5 * (b.x - c.x), 0.5 * cross(b, c) });
  }
  Vec2 best = start;
  double bestValue = smallest(best);
  const size_t m = std::min<size_t>(planes.size(), 16);
  for (size_t i = 0; i < m; ++i)
  {
    for (size_t j = i + 1; j < m; ++j)
    {
      for (size_t k = j + 1; k < m; ++k)
      {
        // area_i(p) = area_j(p) = area_k(p): two linear equations in p.
        const Plane& a = planes[i];
        const Plane& b = planes[j];
        const Plane& c = planes[k];
        const double a11 = a.gx - b.gx, a12 = a.gy - b.gy, r1 = b.c - a.c;
        const double a21 = a.gx - c.gx, a22 = a.gy - c.gy, r2 = c.c - a.c;
        const double det = a11 * a22 - a12 * a21;
        if (std::abs(det) <= 1e-300)
        {
          continue;
        }
        const Vec2 p = { (r1 * a22 - a12 * r2) / det, (a11 * r2 - a21 * r1) / det };
        const double value = smallest(p);
        if (value > bestValue)
        {
          bestValue = value;
          best = p;
        }
      }
    }
  }
  return best;
}

// The rounds of the untangling, for any domain: each round moves every vertex of a flipped
// triangle (`moveVertex(v)` returns whether v moved), plus one more ring of their neighbours
// every 4 rounds, since a vertex whose rim is itself tangled cannot be fixed alone. Returns
// the number of vertices moved.
template <class FindFlipped, class MoveVertex, class TriangleAt>
std::int64_t untangleInRings(const VertexStars& stars, size_t n, FindFlipped findFlipped,
  MoveVertex moveVertex, TriangleAt triangleAt)
{
  std::vector<char> moved(n, 0), inSet(n, 0);
  constexpr int MaximumRounds = 60;
  for (int round = 0; round < MaximumRounds; ++round)
  {
    const std::vector<int> flipped = findFlipped();
    if (flipped.empty())
    {
      break;
    }
    std::vector<int> set;
    auto add = [&](int v)
    {
      if (!inSet[v])
      {
        inSet[v] = 1;
        set.push_back(v);
      }
    };
    for (int t : flipped)
    {
      for (int v : triangleAt(t))
      {
        add(v);
      }
    }
    for (int ring = 0; ring < round / 4; ++ring)
    {
      const size_t count = set.size();
      for (size_t r = 0; r < count; ++r)
      {
        for (int e = stars.offsets[set[r]]; e < stars.offsets[set[r] + 1]; ++e)
        {
          add(stars.entries[e][1]);
          add(stars.entries[e][2]);
        }
      }
    }
    for (int v : set)
    {
      inSet[v] = 0;
      moved[v] |= moveVertex(v);
    }
  }
  return std::count(moved.begin(), moved.end(), 1);
}

// The re-embedding of a collapsed patch, for any domain. Vertex by vertex fails where a whole
// patch collapsed into a thin band (the images of a crowded patch: bunny_holes_35k once in 16
// sample sets, 49 triangles left flipped; the staged transport of a long finger): the patch,
// the vertices within `rings` rings of the flipped triangles that `movable` allows, is laid out
// again as a Tutte embedding (each vertex the average of its neighbours) with every other
// vertex held: a convex combination map, which folds nothing when the held rim is convex (a
// round patch of an otherwise untangled map nearly is). `unknown[v]` becomes v's index in the
// patch, -1 outside.
template <class Movable>
std::vector<int> patchAround(const std::vector<int>& flipped, int rings,
  const std::vector<Triangle>& triangles, const VertexStars& stars, const Movable& movable,
  std::vector<int>& unknown)
{
  std::vector<int> patch;
  auto add = [&](int v)
  {
    if (unknown[v] < 0 && movable(v))
    {
      unknown[v] = static_cast<int>(patch.size());
      patch.push_back(v);
    }
  };
  for (int t : flipped)
  {
    for (int v : triangles[t])
    {
      add(v);
    }
  }
  for (int ring = 0; ring < rings; ++ring)
  {
    const size_t count = patch.size();
    for (size_t r = 0; r < count; ++r)
    {
      for (int e = stars.offsets[patch[r]]; e < stars.offsets[patch[r] + 1]; ++e)
      {
        add(stars.entries[e][1]);
        add(stars.entries[e][2]);
      }
    }
  }
  return patch;
}

// The Tutte positions of `patch` (uniform weights, one per rim edge end), the vertices outside
// it held at `held(u)`: a chart's coordinates. False when the solve fails.
template <class Held>
bool tutteLayout(const VertexStars& stars, const std::vector<int>& patch,
  const std::vector<int>& unknown, const Held& held, std::vector<Vec2>& layout)
{
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(patch.size()), 2);
  for (size_t r = 0; r < patch.size(); ++r)
  {
    const int row = static_cast<int>(r);
    for (int e = stars.offsets[patch[r]]; e < stars.offsets[patch[r] + 1]; ++e)
    {
      for (int k = 1; k < 3; ++k)
      {
        const int u = stars.entries[e][k];
        entries.emplace_back(row, row, 1.0);
        if (unknown[u] >= 0)
        {
          entries.emplace_back(row, unknown[u], -1.0);
        }
        else
        {
          const Vec2 p = held(u);
          rhs(row, 0) += p.x;
          rhs(row, 1) += p.y;
        }
      }
    }
  }
  Eigen::SparseMatrix<double> laplacian(rhs.rows(), rhs.rows());
  laplacian.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplacian);
  const Eigen::MatrixXd position = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !position.allFinite())
  {
    return false;
  }
  layout.resize(patch.size());
  for (size_t r = 0; r < patch.size(); ++r)
  {
    const auto row = static_cast<Eigen::Index>(r);
    layout[r] = { position(row, 0), position(row, 1) };
  }
  return true;
}

// Re-embeds growing patches around the flipped triangles (2 to 32 rings), each kept only if it
// leaves fewer triangles flipped, then untangles locally again. `reembed(flipped, rings)` lays
// one patch out and returns the vertices it moved.
template <class FindFlipped, class Reembed, class UntangleLocally>
std::int64_t reembedWhereCollapsed(
  const FindFlipped& findFlipped, const Reembed& reembed, const UntangleLocally& untangleLocally)
{
  std::int64_t moved = 0;
  for (int rings = 2; rings <= 32; rings *= 2)
  {
    const std::vector<int> flipped = findFlipped();
    if (flipped.empty())
    {
      break;
    }
    moved += reembed(flipped, rings);
    moved += untangleLocally();
  }
  return moved;
}

// Step 2: optimization-based untangling (Freitag and Plassmann): each vertex of a flipped
// triangle moves to the point of its star that maximizes the smallest signed area of its
// triangles, which lies in the kernel of the star's rim whenever that kernel is not empty.
// A vertex whose rim is itself tangled cannot be fixed alone, so the set grows by one ring
// every few rounds. Returns the number of vertices moved.
class Untangler
{
public:
  Untangler(
    const SurfaceMesh& surface, const std::vector<int>& boundaryLoop, const VertexStars& stars)
    : Surface(surface)
    , Stars(stars)
    , Previous(surface.points.size(), -1)
    , Next(surface.points.size(), -1)
  {
    for (size_t k = 0; k < boundaryLoop.size(); ++k)
    {
      const int v = boundaryLoop[k];
      this->Previous[v] = boundaryLoop[(k + boundaryLoop.size() - 1) % boundaryLoop.size()];
      this->Next[v] = boundaryLoop[(k + 1) % boundaryLoop.size()];
    }
  }

  std::int64_t run(std::vector<Vec2>& uv) const
  {
    const std::int64_t moved = this->untangleLocally(uv);
    return moved +
      reembedWhereCollapsed([&] { return flippedTriangles(this->Surface.triangles, uv); },
        [&](const std::vector<int>& flipped, int rings)
        { return this->reembed(flipped, rings, uv); },
        [&] { return this->untangleLocally(uv); });
  }

private:
  std::int64_t untangleLocally(std::vector<Vec2>& uv) const
  {
    return untangleInRings(
      this->Stars, uv.size(), [&] { return flippedTriangles(this->Surface.triangles, uv); },
      [&](int v)
      {
        const Vec2 before = uv[v];
        uv[v] = this->Previous[v] >= 0 ? this->bestOnCircle(v, uv) : this->bestInPlane(v, uv);
        return uv[v].x != before.x || uv[v].y != before.y;
      },
      [&](int t) { return this->Surface.triangles[t]; });
  }

  // The patch around the flipped triangles (the circle's vertices stay) re-embedded in the
  // plane, kept only if fewer triangles are flipped after it. Returns the vertices moved.
  std::int64_t reembed(const std::vector<int>& flipped, int rings, std::vector<Vec2>& uv) const
  {
    std::vector<int> unknown(uv.size(), -1);
    const std::vector<int> patch = patchAround(
      flipped, rings, this->Surface.triangles, this->Stars,
      [&](int v) { return this->Previous[v] < 0; }, unknown);
    std::vector<Vec2> layout;
    if (patch.empty() ||
      !tutteLayout(
        this->Stars, patch, unknown, [&](int u) { return uv[u]; }, layout))
    {
      return 0;
    }
    std::vector<Vec2> before(patch.size());
    for (size_t r = 0; r < patch.size(); ++r)
    {
      before[r] = uv[patch[r]];
      uv[patch[r]] = layout[r];
    }
    if (flippedTriangles(this->Surface.triangles, uv).size() < flipped.size())
    {
      return static_cast<std::int64_t>(patch.size());
    }
    for (size_t r = 0; r < patch.size(); ++r)
    {
      uv[patch[r]] = before[r];
    }
    return 0;
  }

  double smallestArea(int v, Vec2 p, const std::vector<Vec2>& uv) const
  {
    double smallest = HUGE_VAL;
    for (int e = this->Stars.offsets[v]; e < this->Stars.offsets[v + 1]; ++e)
    {
      const auto& entry = this->Stars.entries[e];
      smallest = std::min(smallest, signedArea(p, uv[entry[1]], uv[entry[2]]));
    }
    return smallest;
  }

  Vec2 bestInPlane(int v, const std::vector<Vec2>& uv) const
  {
    std::vector<std::pair<Vec2, Vec2>> rim;
    for (int e = this->Stars.offsets[v]; e < this->Stars.offsets[v + 1]; ++e)
    {
      rim.emplace_back(uv[this->Stars.entries[e][1]], uv[this->Stars.entries[e][2]]);
    }
    return maximizeSmallestArea(rim, uv[v]);
  }

  // Boundary vertices stay on the circle, between their boundary neighbours: the best of a
  // dense set of angles there, refined once around the winner.
  Vec2 bestOnCircle(int v, const std::vector<Vec2>& uv) const
  {
    const Vec2 a = uv[this->Previous[v]], b = uv[this->Next[v]];
    double span = std::atan2(cross(a, b), dot(a, b));
    if (span <= 0.0)
    {
      span += 2.0 * 3.14159265358979323846;
    }
    const double start = std::atan2(a.y, a.x);
    Vec2 best = uv[v];
    double bestValue = this->smallestArea(v, best, uv);
    double low = 0.0, high = 1.0;
    for (int level = 0; level < 3; ++level)
    {
      constexpr int Steps = 32;
      double bestFraction = -1.0;
      for (int s = 1; s < Steps; ++s)
      {
        const double fraction = low + (high - low) * s / Steps;
        const double angle = start + fraction * span;
        const Vec2 p = { std::cos(angle), std::sin(angle) };
        const double value = this->smallestArea(v, p, uv);
        if (value > bestValue)
        {
          bestValue = value;
          best = p;
          bestFraction = fraction;
        }
      }
      if (bestFraction < 0.0)
      {
        break;
      }
      const double width = (high - low) / Steps;
      low = std::max(0.0, bestFraction - width);
      high = std::min(1.0, bestFraction + width);
    }
    return best;
  }

  const SurfaceMesh& Surface;
  const VertexStars& Stars;
  std::vector<int> Previous, Next;
};

} // namespace composition
} // namespace otparam

#endif
