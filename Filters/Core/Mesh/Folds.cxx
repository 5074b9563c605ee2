#include "Mesh/Folds.h"

#include "Common/DirectedEdges.h"
#include "Common/SegmentCrossings.h"
#include "Common/SphericalGeometry.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>

namespace otparam
{
using HoleKernel = CGAL::Exact_predicates_inexact_constructions_kernel;

bool positive(const std::vector<Vec2>& uv, const Triangle& t)
{
  return cross(uv[t[1]] - uv[t[0]], uv[t[2]] - uv[t[0]]) > 0.0;
}

bool positive(const std::vector<Vec3>& x, const Triangle& t)
{
  return sphericalTriangleArea(x[t[0]], x[t[1]], x[t[2]]) > 0.0;
}

namespace
{
template <class Point>
bool anyNotPositive(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  return std::any_of(triangles.begin(), triangles.end(),
    [&points](const Triangle& t) { return !positive(points, t); });
}
} // namespace

bool anyFolded(const std::vector<Vec2>& uv, const std::vector<Triangle>& triangles)
{
  return anyNotPositive(uv, triangles);
}

bool anyFolded(const std::vector<Vec3>& x, const std::vector<Triangle>& triangles)
{
  return anyNotPositive(x, triangles);
}

namespace
{
// The directed edges a -> b of the triangles inPatch that no other such triangle shares: the
// patch's boundary, with the patch on the left; `owners` (when given) gets each edge's triangle.
std::vector<std::pair<int, int>> boundaryEdges(const std::vector<Triangle>& triangles,
  const std::vector<bool>& inPatch, std::vector<int>* owners = nullptr)
{
  std::vector<Triangle> patch;
  std::vector<int> patchIds;
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    if (inPatch[t])
    {
      patch.push_back(triangles[t]);
      patchIds.push_back(static_cast<int>(t));
    }
  }
  const auto edges = sortedDirectedEdges(patch);
  std::vector<std::pair<int, int>> boundary;
  for (size_t e = 0; e < edges.size();)
  {
    size_t next = e + 1;
    while (next < edges.size() && edges[next].first >> 1 == edges[e].first >> 1)
    {
      ++next;
    }
    if (next == e + 1)
    {
      const Triangle& tri = patch[edges[e].second / 3];
      const int k = edges[e].second % 3;
      boundary.emplace_back(tri[k], tri[(k + 1) % 3]);
      if (owners)
      {
        owners->push_back(patchIds[edges[e].second / 3]);
      }
    }
    e = next;
  }
  return boundary;
}

// The rim of the patch (the triangles inPatch) as a map a -> b, when it is one simple loop;
// empty otherwise.
std::map<int, int> patchRim(
  const std::vector<Triangle>& triangles, const std::vector<bool>& inPatch)
{
  std::map<int, int> rim;
  for (const auto& [a, b] : boundaryEdges(triangles, inPatch))
  {
    if (!rim.emplace(a, b).second)
    {
      return {}; // a vertex where the rim touches itself
    }
  }
  // One loop: following it from a rim vertex comes back after visiting every rim vertex.
  std::size_t steps = 0;
  for (int v = rim.empty() ? -1 : rim.begin()->first; steps < rim.size();)
  {
    const auto next = rim.find(v);
    if (next == rim.end())
    {
      return {};
    }
    v = next->second;
    ++steps;
    if (v == rim.begin()->first)
    {
      break;
    }
  }
  return steps == rim.size() ? rim : std::map<int, int>{};
}

// The direction of a rim's mean point, or false when its points cancel out.
bool rimCentre(const std::vector<Vec3>& points, const std::map<int, int>& rim, Vec3& centre)
{
  Vec3 sum{};
  for (const auto& edge : rim)
  {
    sum = sum + points[edge.first];
  }
  if (rim.empty() || !(norm(sum) > 1e-3))
  {
    return false;
  }
  centre = normalized(sum);
  return true;
}

// Whether the fan (a, b, centre) is positive for every rim edge a -> b.
bool fanPositive(const std::vector<Vec3>& points, const std::map<int, int>& rim, Vec3 centre)
{
  return std::all_of(rim.begin(), rim.end(),
    [&](const std::pair<const int, int>& edge)
    { return sphericalTriangleArea(points[edge.first], points[edge.second], centre) > 0.0; });
}

// The rim's loop triangulated without new points where no fan is positive (a rim that is not
// star-shaped about its centre): CGAL's hole filling (minimal area) of the loop in the gnomonic
// chart at `centre`, kept when every triangle is positive on the sphere.
bool triangulateRim(const std::vector<Vec3>& points, const std::map<int, int>& rim, Vec3 centre,
  std::vector<Triangle>& fill)
{
  // The hole filling's search is cubic in the loop's length.
  constexpr std::size_t LongestTriangulatedRim = 64;
  if (rim.size() < 3 || rim.size() > LongestTriangulatedRim)
  {
    return false;
  }
  Vec3 e1, e2;
  tangentFrame(centre, e1, e2);
  std::vector<int> loop;
  std::vector<HoleKernel::Point_3> polyline;
  for (int v = rim.begin()->first; loop.size() < rim.size(); v = rim.at(v))
  {
    const double height = dot(points[v], centre);
    if (!(height > 0.05))
    {
      return false; // beyond the chart
    }
    loop.push_back(v);
    polyline.emplace_back(dot(points[v], e1) / height, dot(points[v], e2) / height, 0.0);
  }
  std::vector<CGAL::Triple<int, int, int>> faces;
  CGAL::Polygon_mesh_processing::triangulate_hole_polyline(polyline, std::back_inserter(faces));
  if (faces.size() + 2 != loop.size())
  {
    return false;
  }
  // The fill takes the patch's side of each rim edge a -> b (in a's and b's order).
  const auto follows = [&](int a, int b) { return b == (a + 1) % static_cast<int>(loop.size()); };
  bool reversed = false;
  for (const auto& face : faces)
  {
    if (follows(face.second, face.first) || follows(face.third, face.second) ||
      follows(face.first, face.third))
    {
      reversed = true;
      break;
    }
  }
  for (const auto& face : faces)
  {
    fill.push_back({ loop[face.first], loop[reversed ? face.third : face.second],
      loop[reversed ? face.second : face.third] });
  }
  return std::all_of(
    fill.begin(), fill.end(), [&](const Triangle& t) { return positive(points, t); });
}
} // namespace

namespace
{
// Drops the kept triangles at a vertex where two fans of them meet (a pinch a sampler's
// domain cannot have), until there is none.
void dropPinches(
  const std::vector<Triangle>& triangles, std::size_t points, std::vector<bool>& kept)
{
  bool pinched = std::find(kept.begin(), kept.end(), false) != kept.end();
  while (pinched)
  {
    // A vertex on more than two boundary edges of the kept triangles pinches their domain.
    std::vector<int> boundaryEdgesAt(points, 0);
    for (const auto& [a, b] : boundaryEdges(triangles, kept))
    {
      ++boundaryEdgesAt[a];
      ++boundaryEdgesAt[b];
    }
    pinched = false;
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      for (int k = 0; kept[t] && k < 3; ++k)
      {
        if (boundaryEdgesAt[triangles[t][k]] > 2)
        {
          kept[t] = false;
          pinched = true;
        }
      }
    }
  }
}

// Drops the kept triangles whose boundary edges cross other boundary edges (positive triangles
// overlapping across a fold), and any pinch that leaves; crossings left after MaximumPeels
// rounds, the sampler names.
void peelCrossings(
  const std::vector<Vec2>& uv, const std::vector<Triangle>& triangles, std::vector<bool>& kept)
{
  constexpr int MaximumPeels = 64;
  for (int peel = 0; peel < MaximumPeels; ++peel)
  {
    std::vector<int> owners;
    const std::vector<std::pair<int, int>> edges = boundaryEdges(triangles, kept, &owners);
    const std::vector<std::pair<int, int>> crossings = crossingSegments(uv, edges);
    if (crossings.empty())
    {
      return;
    }
    for (const auto& [e, f] : crossings)
    {
      kept[owners[e]] = kept[owners[f]] = false;
    }
    dropPinches(triangles, uv.size(), kept);
  }
}
} // namespace

std::vector<bool> unfoldedPart(
  const std::vector<Vec2>& uv, const std::vector<Triangle>& triangles, bool peel)
{
  if (!anyFolded(uv, triangles))
  {
    return std::vector<bool>(triangles.size(), true); // an unfolded map is kept whole
  }
  std::vector<bool> kept(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    kept[t] = positive(uv, triangles[t]);
  }
  dropPinches(triangles, uv.size(), kept);
  if (peel)
  {
    peelCrossings(uv, triangles, kept);
  }
  return kept;
}

namespace
{
// The triangles sharing a vertex, directly or through others, with `seed`'s and as not
// positive as it: one fold.
std::vector<bool> foldAround(const std::vector<Vec3>& points,
  const std::vector<Triangle>& triangles, const std::vector<bool>& notPositive, std::size_t seed)
{
  std::vector<bool> inFold(triangles.size(), false), foldVertex(points.size(), false);
  inFold[seed] = true;
  for (bool grew = true; grew;)
  {
    grew = false;
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      const Triangle& tri = triangles[t];
      if (inFold[t])
      {
        for (int v : tri)
        {
          grew = grew || !foldVertex[v];
          foldVertex[v] = true;
        }
      }
      else if (notPositive[t] && (foldVertex[tri[0]] || foldVertex[tri[1]] || foldVertex[tri[2]]))
      {
        inFold[t] = grew = true;
      }
    }
  }
  return inFold;
}

// Whether a rim triangulation's diagonal is already an edge outside the patch (two rim vertices
// joined around it): the mesh would no longer be a closed surface.
bool diagonalOutside(const std::vector<Triangle>& triangles, const std::vector<bool>& inPatch,
  const std::map<int, int>& rim, const std::vector<Triangle>& fill)
{
  const auto undirected = [](int a, int b)
  { return std::make_pair(std::min(a, b), std::max(a, b)); };
  std::set<std::pair<int, int>> diagonals;
  for (const Triangle& t : fill)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = t[k], b = t[(k + 1) % 3];
      const auto along = rim.find(a), against = rim.find(b);
      if (!(along != rim.end() && along->second == b) &&
        !(against != rim.end() && against->second == a))
      {
        diagonals.insert(undirected(a, b));
      }
    }
  }
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    for (int k = 0; !inPatch[t] && k < 3; ++k)
    {
      if (diagonals.count(undirected(triangles[t][k], triangles[t][(k + 1) % 3])))
      {
        return true;
      }
    }
  }
  return false;
}

// The fold's patch grown ring by ring (up to 8) until its rim is one loop from whose centre a
// fan is positive, or which CGAL's hole filling triangulates with positive triangles, and
// replaced by that fan or fill; false when no ring gives one.
bool replacePatch(std::vector<Vec3>& points, std::vector<Triangle>& triangles,
  std::vector<double>& density, std::vector<bool> inPatch)
{
  for (int ring = 0; ring < 8; ++ring)
  {
    // One more ring: every triangle touching a vertex of the patch.
    std::vector<bool> patchVertex(points.size(), false);
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      for (int k = 0; inPatch[t] && k < 3; ++k)
      {
        patchVertex[triangles[t][k]] = true;
      }
    }
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      const Triangle& tri = triangles[t];
      inPatch[t] = patchVertex[tri[0]] || patchVertex[tri[1]] || patchVertex[tri[2]];
    }
    const std::map<int, int> rim = patchRim(triangles, inPatch);
    std::vector<Triangle> fill;
    Vec3 centre;
    if (!rimCentre(points, rim, centre))
    {
      continue;
    }
    const bool fan = fanPositive(points, rim, centre);
    if (!fan &&
      (!triangulateRim(points, rim, centre, fill) ||
        diagonalOutside(triangles, inPatch, rim, fill)))
    {
      continue;
    }
    std::vector<Triangle> healed;
    std::vector<double> healedDensity;
    double patchDensity = 0.0;
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      patchDensity = inPatch[t] ? std::max(patchDensity, density[t]) : patchDensity;
      if (!inPatch[t])
      {
        healed.push_back(triangles[t]);
        healedDensity.push_back(density[t]);
      }
    }
    if (fan)
    {
      const int centreId = static_cast<int>(points.size());
      for (const auto& [a, b] : rim)
      {
        fill.push_back({ a, b, centreId });
      }
      points.push_back(centre);
    }
    healed.insert(healed.end(), fill.begin(), fill.end());
    healedDensity.resize(healed.size(), patchDensity);
    triangles.swap(healed);
    density.swap(healedDensity);
    return true;
  }
  return false;
}
} // namespace

void healSphereFolds(
  std::vector<Vec3>& points, std::vector<Triangle>& triangles, std::vector<double>& density)
{
  if (!anyFolded(points, triangles))
  {
    return;
  }
  std::vector<bool> notPositive(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    notPositive[t] = !positive(points, triangles[t]);
  }
  if (replacePatch(points, triangles, density, notPositive))
  {
    return;
  }
  // Folds apart, healed apart (a stage's composition can leave dozens of a few triangles each,
  // which no one fan covers): each patch replaced before the next is sought.
  std::vector<bool> tried(triangles.size(), false); // folds no patch around could replace
  for (std::size_t seed = 0; seed < triangles.size();)
  {
    if (tried[seed] || positive(points, triangles[seed]))
    {
      ++seed;
      continue;
    }
    std::vector<bool> folded(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      folded[t] = !positive(points, triangles[t]);
    }
    const std::vector<bool> fold = foldAround(points, triangles, folded, seed);
    if (replacePatch(points, triangles, density, fold))
    {
      tried.assign(triangles.size(), false); // renumbered: every fold is sought again
      seed = 0;
      continue;
    }
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      tried[t] = tried[t] || fold[t];
    }
    ++seed;
  }
}

} // namespace otparam
