// The directed edges of a triangle list in linear time, sorted so that the two directions of an
// edge (and any repeat of one direction) sit side by side: the mesh checks (Mesh/SurfaceMesh)
// and the density field's overlap check (Sampling/PlanarDensityField) read them.
#ifndef OTPARAM_COMMON_DIRECTEDEDGES_H
#define OTPARAM_COMMON_DIRECTEDEDGES_H

#include "Common/Geometry.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace otparam
{

// The undirected edge, then the direction: (min, max, a > b).
inline std::uint64_t directedEdgeKey(int a, int b)
{
  const std::uint64_t low = static_cast<std::uint32_t>(std::min(a, b));
  const std::uint64_t high = static_cast<std::uint32_t>(std::max(a, b));
  return ((low << 32 | high) << 1) | (a > b ? 1u : 0u);
}

// (directedEdgeKey(a, b), 3 t + k) for the edge from corner k to corner k + 1 of triangle t,
// sorted. Bucketed by the edge's lower vertex (a counting sort), then each bucket (a vertex's
// few edges) sorted: the order of one sort of the whole array, in linear time (1.09M points:
// 6.6M directed edges, 0.43 -> 0.10 s).
inline std::vector<std::pair<std::uint64_t, int>> sortedDirectedEdges(
  const std::vector<Triangle>& triangles)
{
  int vertices = 0;
  for (const Triangle& t : triangles)
  {
    vertices = std::max({ vertices, t[0] + 1, t[1] + 1, t[2] + 1 });
  }
  std::vector<int> start(static_cast<size_t>(vertices) + 1, 0);
  for (const Triangle& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::pair<std::uint64_t, int>> edges(3 * triangles.size());
  std::vector<int> next(start.begin(), start.end() - 1);
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      edges[next[std::min(a, b)]++] = { directedEdgeKey(a, b), static_cast<int>(3 * t + k) };
    }
  }
  for (int v = 0; v < vertices; ++v)
  {
    std::sort(edges.begin() + start[v], edges.begin() + start[v + 1]);
  }
  return edges;
}

} // namespace otparam

#endif
