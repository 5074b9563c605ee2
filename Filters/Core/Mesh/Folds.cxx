#include "Mesh/Folds.h"

#include "Common/DirectedEdges.h"
#include "Common/SegmentCrossings.h"
#include "Common/SphericalGeometry.h"

#include <algorithm>
#include <map>
#include <utility>

namespace otparam
{

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

// The centre on the sphere of a rim around which the fan (a, b, centre) is positive for every
// rim edge a -> b, or false.
bool fanCentre(const std::vector<Vec3>& points, const std::map<int, int>& rim, Vec3& centre)
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
  return std::all_of(rim.begin(), rim.end(),
    [&](const std::pair<const int, int>& edge)
    { return sphericalTriangleArea(points[edge.first], points[edge.second], centre) > 0.0; });
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

void healSphereFolds(
  std::vector<Vec3>& points, std::vector<Triangle>& triangles, std::vector<double>& density)
{
  if (!anyFolded(points, triangles))
  {
    return;
  }
  std::vector<bool> inPatch(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    inPatch[t] = !positive(points, triangles[t]);
  }
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
    Vec3 centre;
    if (!fanCentre(points, rim, centre))
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
    const int centreId = static_cast<int>(points.size());
    for (const auto& [a, b] : rim)
    {
      healed.push_back({ a, b, centreId });
      healedDensity.push_back(patchDensity);
    }
    points.push_back(centre);
    triangles.swap(healed);
    density.swap(healedDensity);
    return;
  }
}

} // namespace otparam
