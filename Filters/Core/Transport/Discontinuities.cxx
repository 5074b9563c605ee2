#include "Transport/Discontinuities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>

namespace otparam
{
namespace
{
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int orientation(Vec2 a, Vec2 b, Vec2 c)
{
  return static_cast<int>(
    CGAL::orientation(K::Point_2(a.x, a.y), K::Point_2(b.x, b.y), K::Point_2(c.x, c.y)));
}

// For p on the line through o and target: p lies on the target's side of o.
bool dotAlong(Vec2 o, Vec2 p, Vec2 target)
{
  return dot(p - o, target - o) > 0.0;
}
} // namespace

SupportTriangulation::SupportTriangulation(
  const std::vector<Vec2>& diracs, const std::vector<Triangle>& triangles)
  : Points(diracs)
  , Incident(diracs.size())
{
  for (Triangle t : triangles)
  {
    if (orientation(Points[t[0]], Points[t[1]], Points[t[2]]) == 0)
    {
      continue; // a flat triangle covers nothing
    }
    if (orientation(Points[t[0]], Points[t[1]], Points[t[2]]) < 0)
    {
      std::swap(t[1], t[2]);
    }
    for (int v : t)
    {
      Incident[v].push_back(static_cast<int>(Triangles.size()));
    }
    Triangles.push_back(t);
  }
}

int SupportTriangulation::neighbourAcross(int t, int a, int b) const
{
  for (int u : Incident[a])
  {
    if (u == t)
    {
      continue;
    }
    const Triangle& tri = Triangles[u];
    if (std::find(tri.begin(), tri.end(), b) != tri.end())
    {
      return u;
    }
  }
  return -1;
}

// A straight walk from y_i towards y_j through the triangles: it fails where it would have to
// leave the union of the triangles (a boundary edge crossed, or no triangle in the direction of
// y_j at a vertex it passes through). Written by hand: CGAL's line walk needs a triangulation of
// the convex hull, which the support (holes, several components) is not.
bool SupportTriangulation::segmentInside(int i, int j) const
{
  const Vec2 target = Points[j];
  int vertex = i;                // the walk stands at a vertex...
  int face = -1, a = -1, b = -1; // ...or has entered `face` through its edge ab
  const std::size_t limit = 2 * (Triangles.size() + Points.size()) + 8;
  for (std::size_t step = 0; step < limit; ++step)
  {
    if (vertex >= 0)
    {
      if (vertex == j)
      {
        return true;
      }
      const Vec2 o = Points[vertex];
      int next = -1, nextVertex = -1;
      for (int t : Incident[vertex])
      {
        const Triangle& tri = Triangles[t];
        const int k = static_cast<int>(std::find(tri.begin(), tri.end(), vertex) - tri.begin());
        const int p = tri[(k + 1) % 3], q = tri[(k + 2) % 3]; // o, p, q counter-clockwise
        const int sp = orientation(o, Points[p], target), sq = orientation(o, Points[q], target);
        if (sp == 0 && dotAlong(o, Points[p], target))
        {
          nextVertex = p; // along the edge op
          break;
        }
        if (sq == 0 && dotAlong(o, Points[q], target))
        {
          nextVertex = q;
          break;
        }
        if (sp > 0 && sq < 0)
        {
          next = t; // strictly inside the wedge at o
          a = p;
          b = q;
          break;
        }
      }
      if (nextVertex >= 0)
      {
        // Past the target along that edge cannot happen for distinct Diracs unless the target
        // lies on the edge, which a triangulation of the Diracs does not allow.
        vertex = nextVertex;
        continue;
      }
      if (next < 0)
      {
        return false; // no triangle of the support in that direction
      }
      face = next; // the segment leaves it across ab (it cannot end inside: j is a vertex)
      vertex = -1;
    }
    else
    {
      // Entered across ab into the neighbour: find the third vertex c of the new face.
      const int nb = neighbourAcross(face, a, b);
      if (nb < 0)
      {
        return false; // ab is a boundary edge of the support
      }
      const Triangle& tri = Triangles[nb];
      int c = -1;
      for (int v : tri)
      {
        c = v != a && v != b ? v : c;
      }
      if (c == j)
      {
        return true;
      }
      const int sc = orientation(Points[i], target, Points[c]);
      if (sc == 0)
      {
        vertex = c; // through the vertex c
        face = -1;
        continue;
      }
      // Leave through ac or cb: the side of the line on which c lies.
      const int sa = orientation(Points[i], target, Points[a]);
      if (sc == sa)
      {
        a = c;
      }
      else
      {
        b = c;
      }
      face = nb;
    }
  }
  return false;
}

std::vector<PowerDiagramGeometry::Edge> discontinuityEdges(const PowerDiagramGeometry& geometry,
  const std::vector<Vec2>& diracs, const std::vector<Triangle>& support)
{
  const SupportTriangulation triangulation(diracs, support);
  std::vector<PowerDiagramGeometry::Edge> jumps;
  for (const PowerDiagramGeometry::Edge& e : geometry.edges)
  {
    if (norm(e.b - e.a) > 0.0 && !triangulation.segmentInside(e.i, e.j))
    {
      jumps.push_back(e);
    }
  }
  return jumps;
}

} // namespace otparam
