// Point location in a planar triangulation by a short walk from a seed triangle, for the
// density field's queries (Sampling/PlanarDensityField), which a box-tree search answered alone:
// ~10% of the sampler's time at 2e5 samples. The walk answers only where it cannot differ from
// the search (see locate); elsewhere the caller searches as before.
#ifndef OTPARAM_COMMON_TRIANGLEWALK_H
#define OTPARAM_COMMON_TRIANGLEWALK_H

#include "Common/DirectedEdges.h"
#include "Common/Geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace otparam
{

class TriangleWalk
{
public:
  TriangleWalk() = default;

  // `triangles` counter-clockwise and not overlapping.
  TriangleWalk(const std::vector<Vec2>& points, const std::vector<Triangle>& triangles)
  {
    if (triangles.empty())
    {
      return;
    }
    this->findNeighbours(triangles);
    Vec2 lo = points[triangles[0][0]], hi = lo;
    double squaredDiameter = 0.0;
    for (const Triangle& t : triangles)
    {
      for (int k = 0; k < 3; ++k)
      {
        const Vec2 p = points[t[k]], edge = points[t[(k + 1) % 3]] - p;
        lo = { std::min(lo.x, p.x), std::min(lo.y, p.y) };
        hi = { std::max(hi.x, p.x), std::max(hi.y, p.y) };
        squaredDiameter = std::max(squaredDiameter, dot(edge, edge));
      }
    }
    // A point inside the triangles' set only up to the search's slack (barycentric -1e-12)
    // lies within 3e-12 of a triangle's diameter from it; a point further than this inside one
    // triangle is in no other's slack (see locate).
    this->Margin = 1e-9 * std::sqrt(squaredDiameter);
    const double width = std::max(hi.x - lo.x, hi.y - lo.y);
    const int cells = std::max(1, static_cast<int>(std::sqrt(triangles.size() / SeedShare)));
    if (!(width > 0.0) || !(this->Margin > 0.0))
    {
      return;
    }
    this->Lo = lo;
    this->CellSize = width / cells;
    this->Columns = std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) / this->CellSize)));
    this->Rows = std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) / this->CellSize)));
    this->placeSeeds(points, triangles);
  }

  // False for a default-constructed walk, which answers nothing.
  bool built() const { return !this->Seeds.empty(); }

  // The triangle holding x at more than Margin from each of its edges, or -1 (the walk left the
  // triangles, took more than MaximumSteps, or ended near an edge). Such a triangle is the only
  // one whose barycentric coordinates at x are all >= -1e-12: any other lies outside it (they
  // do not overlap), so at least Margin from x, while that slack reaches 3e-12 of a triangle's
  // diameter beyond it. So the box-tree search, which takes the first triangle it meets within
  // that slack, would find this one too.
  int locate(Vec2 x, const std::vector<Vec2>& points, const std::vector<Triangle>& triangles) const
  {
    if (this->Seeds.empty())
    {
      return -1;
    }
    int t = this->Seeds[this->cellOf(x)];
    for (int step = 0; t >= 0 && step < MaximumSteps; ++step)
    {
      const Triangle& tri = triangles[t];
      // Twice the signed area of x with each edge (corner k to k + 1), positive inside; the
      // walk crosses the first edge that has x outside (a visibility walk).
      std::array<double, 3> side;
      int across = -1;
      for (int k = 0; k < 3 && across < 0; ++k)
      {
        const Vec2 a = points[tri[k]], b = points[tri[(k + 1) % 3]];
        side[k] = cross(b - a, x - a);
        across = side[k] < 0.0 ? k : -1;
      }
      if (across >= 0)
      {
        t = this->Neighbours[t][across];
        continue;
      }
      for (int k = 0; k < 3; ++k)
      {
        const Vec2 a = points[tri[k]], b = points[tri[(k + 1) % 3]];
        // Distance to the edge's line over Margin, as a comparison of squares.
        if (!(side[k] * side[k] > this->Margin * this->Margin * dot(b - a, b - a)))
        {
          return -1; // near an edge (or an edge too short for its square): for the search
        }
      }
      return t;
    }
    return -1;
  }

  // Calls visit(t) for every triangle that meets the counter-clockwise triangle abc, from
  // `seed`, one that meets it, across the edges that meet it, up to a few units in the last
  // place (a triangle that meets abc is reached so: abc is convex and the triangles do not
  // overlap). False, some triangles unvisited, when that reaches the triangles' boundary (abc
  // may leave their union, or meet another part of it) or more than MaximumVisits triangles.
  template <typename Visit>
  bool visitMeeting(int seed, Vec2 a, Vec2 b, Vec2 c, const std::vector<Vec2>& points,
    const std::vector<Triangle>& triangles, const Visit& visit) const
  {
    std::array<int, MaximumVisits> found;
    int count = 0;
    found[count++] = seed;
    for (int next = 0; next < count; ++next)
    {
      const int t = found[next];
      visit(t);
      const Triangle& tri = triangles[t];
      for (int k = 0; k < 3; ++k)
      {
        if (!segmentMayMeet(points[tri[k]], points[tri[(k + 1) % 3]], a, b, c))
        {
          continue;
        }
        const int across = this->Neighbours[t][k];
        if (across < 0)
        {
          return false;
        }
        if (std::find(found.begin(), found.begin() + count, across) == found.begin() + count)
        {
          if (count == MaximumVisits)
          {
            return false;
          }
          found[count++] = across;
        }
      }
    }
    return true;
  }

private:
  // Triangles per seed cell: walks of a few steps where the triangles are even; where they
  // crowd (a conformal image's extremities), walks give up after MaximumSteps.
  static constexpr double SeedShare = 2.0;
  static constexpr int MaximumSteps = 24;
  // A search over more triangles is left to a box tree, which prunes by their values.
  static constexpr int MaximumVisits = 48;

  // False only when a line through an edge of the counter-clockwise abc, or through pq, has
  // the one on one side and the other on the other, apart by more than rounding (convex shapes
  // that do not meet are separated by a line through an edge of one of them).
  static bool segmentMayMeet(Vec2 p, Vec2 q, Vec2 a, Vec2 b, Vec2 c)
  {
    for (const auto& [u, v] : { std::pair{ a, b }, std::pair{ b, c }, std::pair{ c, a } })
    {
      if (rightOfBeyondRounding(u, v, p) && rightOfBeyondRounding(u, v, q))
      {
        return false;
      }
    }
    return !(rightOfBeyondRounding(p, q, a) && rightOfBeyondRounding(p, q, b) &&
             rightOfBeyondRounding(p, q, c)) &&
      !(rightOfBeyondRounding(q, p, a) && rightOfBeyondRounding(q, p, b) &&
        rightOfBeyondRounding(q, p, c));
  }

  int cellOf(Vec2 x) const
  {
    const int column = std::clamp(
      static_cast<int>(std::floor((x.x - this->Lo.x) / this->CellSize)), 0, this->Columns - 1);
    const int row = std::clamp(
      static_cast<int>(std::floor((x.y - this->Lo.y) / this->CellSize)), 0, this->Rows - 1);
    return row * this->Columns + column;
  }

  // Each cell's seed: the first triangle whose centroid falls in it; a cell with none (where
  // triangles are larger than the cells, or outside them) takes the nearest such cell's. (Searching
  // a box tree at every cell's centre cost ~40 ms at hand_choi_53k's 53k triangles, a fifth of its
  // sampler.)
  void placeSeeds(const std::vector<Vec2>& points, const std::vector<Triangle>& triangles)
  {
    this->Seeds.assign(static_cast<size_t>(this->Columns) * this->Rows, -1);
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      const Triangle& tri = triangles[t];
      int& seed =
        this->Seeds[this->cellOf((1.0 / 3.0) * (points[tri[0]] + points[tri[1]] + points[tri[2]]))];
      seed = seed < 0 ? static_cast<int>(t) : seed;
    }
    // Breadth first from the cells that have one: each empty cell takes the seed of the
    // neighbour it is first reached from.
    std::vector<int> queue;
    for (size_t cell = 0; cell < this->Seeds.size(); ++cell)
    {
      if (this->Seeds[cell] >= 0)
      {
        queue.push_back(static_cast<int>(cell));
      }
    }
    for (size_t next = 0; next < queue.size(); ++next)
    {
      const int cell = queue[next], row = cell / this->Columns, column = cell % this->Columns;
      for (const auto& [dr, dc] : { std::pair{ 0, -1 }, { -1, 0 }, { 0, 1 }, { 1, 0 } })
      {
        const int r = row + dr, c = column + dc;
        if (r >= 0 && r < this->Rows && c >= 0 && c < this->Columns &&
          this->Seeds[r * this->Columns + c] < 0)
        {
          this->Seeds[r * this->Columns + c] = this->Seeds[cell];
          queue.push_back(r * this->Columns + c);
        }
      }
    }
  }

  void findNeighbours(const std::vector<Triangle>& triangles)
  {
    this->Neighbours.assign(triangles.size(), { -1, -1, -1 });
    const std::vector<std::pair<std::uint64_t, int>> edges = sortedDirectedEdges(triangles);
    for (size_t e = 0; e + 1 < edges.size(); ++e)
    {
      // The two directions of one edge, side by side (their keys differ in the lowest bit).
      if ((edges[e].first >> 1) == (edges[e + 1].first >> 1) &&
        edges[e].first != edges[e + 1].first)
      {
        const int a = edges[e].second, b = edges[e + 1].second;
        this->Neighbours[a / 3][a % 3] = b / 3;
        this->Neighbours[b / 3][b % 3] = a / 3;
      }
    }
  }

  std::vector<std::array<int, 3>> Neighbours; // across the edge from corner k to k + 1
  std::vector<int> Seeds;                     // a triangle at or near each grid cell
  Vec2 Lo;
  double CellSize = 0.0, Margin = 0.0;
  int Columns = 0, Rows = 0;
};

} // namespace otparam

#endif
