#include "Mesh/DiskPatch.h"

#include "Common/DirectedEdges.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <unordered_map>
#include <utility>

namespace otparam
{

namespace
{
// The topology of a patch growing triangle by triangle, in constant time per triangle: on a
// genus-0 surface a connected patch is a disk when V - E + F = 1 and every boundary vertex has
// two boundary edges (no pinch; then its boundary is one loop).
class GrowingPatch
{
public:
  explicit GrowingPatch(std::size_t points)
    : VertexUses(points, 0)
    , BoundaryEdgesAt(points, 0)
  {
  }

  void add(const Triangle& t)
  {
    ++this->Faces;
    for (int k = 0; k < 3; ++k)
    {
      this->Vertices += this->VertexUses[t[k]]++ == 0;
      const int a = t[k], b = t[(k + 1) % 3];
      const int uses = ++this->EdgeUses[directedEdgeKey(a, b) >> 1]; // the undirected edge
      this->Edges += uses == 1;
      for (int v : { a, b })
      {
        this->Pinches -= this->pinched(v);
        this->BoundaryEdgesAt[v] += uses == 1 ? 1 : -1; // a new boundary edge, or one closed
        this->Pinches += this->pinched(v);
      }
    }
  }

  bool isDisk() const
  {
    return this->Vertices - this->Edges + this->Faces == 1 && this->Pinches == 0;
  }

private:
  bool pinched(int v) const
  {
    return this->BoundaryEdgesAt[v] != 0 && this->BoundaryEdgesAt[v] != 2;
  }

  std::vector<int> VertexUses, BoundaryEdgesAt;
  std::unordered_map<std::uint64_t, int> EdgeUses;
  std::int64_t Vertices = 0, Edges = 0, Faces = 0, Pinches = 0;
};

// What growing patches reads of the mesh, made once for all of bodyPatch's candidates.
struct TriangleFans
{
  std::vector<std::vector<int>> trianglesAt; // per point
  std::vector<double> area;                  // per triangle
  double total = 0.0;

  explicit TriangleFans(const SurfaceMesh& mesh)
    : trianglesAt(mesh.points.size())
    , area(mesh.triangles.size())
  {
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
    {
      for (int v : mesh.triangles[t])
      {
        this->trianglesAt[v].push_back(static_cast<int>(t));
      }
      this->area[t] = triangleArea(mesh, mesh.triangles[t]);
      this->total += this->area[t];
    }
  }
};

// growDiskPatch on the fans.
std::vector<char> growDiskPatchOn(
  const SurfaceMesh& mesh, const TriangleFans& fans, int centre, double share)
{
  // Rings of vertices around the centre (the corners of the last ring's triangles), their
  // triangles added ring by ring; the patch of the last ring at which it was a disk is kept.
  std::vector<char> reached(mesh.points.size(), 0), added(mesh.triangles.size(), 0);
  std::vector<int> order, ring = { centre };
  reached[centre] = 1;
  GrowingPatch topology(mesh.points.size());
  std::size_t diskEnd = 0;
  double patchArea = 0.0;
  while (!ring.empty() && patchArea < share * fans.total)
  {
    std::vector<int> next;
    for (int v : ring)
    {
      for (int t : fans.trianglesAt[v])
      {
        if (!added[t])
        {
          added[t] = 1;
          order.push_back(t);
          topology.add(mesh.triangles[t]);
          patchArea += fans.area[t];
        }
        for (int w : mesh.triangles[t])
        {
          if (!reached[w])
          {
            reached[w] = 1;
            next.push_back(w);
          }
        }
      }
    }
    diskEnd = topology.isDisk() ? order.size() : diskEnd;
    ring.swap(next);
  }
  std::vector<char> patch;
  if (diskEnd > 0)
  {
    patch.assign(mesh.triangles.size(), 0);
    for (std::size_t k = 0; k < diskEnd; ++k)
    {
      patch[order[k]] = 1;
    }
  }
  return patch;
}

struct Neighbour
{
  int point;
  double length;
};

std::vector<std::vector<Neighbour>> edgeGraph(const SurfaceMesh& mesh)
{
  std::vector<std::vector<Neighbour>> graph(mesh.points.size());
  for (const Triangle& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      // A closed surface's edge is met once in each direction, by its two triangles.
      const int a = t[k], b = t[(k + 1) % 3];
      graph[a].push_back({ b, norm(mesh.points[b] - mesh.points[a]) });
    }
  }
  return graph;
}

// A patch that stops growing below this share of its target wrapped around a protrusion (a
// tube's rings stop being disks once they close around it).
constexpr double BodyPatchReach = 0.8;

// Dijkstra's distances along the edges from `source`.
std::vector<double> distancesFrom(const std::vector<std::vector<Neighbour>>& graph, int source)
{
  std::vector<double> distance(graph.size(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  distance[source] = 0.0;
  queue.push({ 0.0, source });
  while (!queue.empty())
  {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v])
    {
      continue;
    }
    for (const Neighbour& n : graph[v])
    {
      if (d + n.length < distance[n.point])
      {
        distance[n.point] = d + n.length;
        queue.push({ distance[n.point], n.point });
      }
    }
  }
  return distance;
}

// The length of a patch's boundary; `area` gets its area.
double boundaryLength(
  const SurfaceMesh& mesh, const TriangleFans& fans, const std::vector<char>& inPatch, double& area)
{
  std::map<std::pair<int, int>, int> edgeUses;
  area = 0.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    if (!inPatch[t])
    {
      continue;
    }
    const Triangle& tri = mesh.triangles[t];
    area += fans.area[t];
    for (int k = 0; k < 3; ++k)
    {
      const int a = tri[k], b = tri[(k + 1) % 3];
      ++edgeUses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  double length = 0.0;
  for (const auto& [edge, uses] : edgeUses)
  {
    length += uses == 1 ? norm(mesh.points[edge.second] - mesh.points[edge.first]) : 0.0;
  }
  return length;
}

// A patch's boundary length over the square root of its area (`area`).
double roundness(
  const SurfaceMesh& mesh, const TriangleFans& fans, const std::vector<char>& inPatch, double& area)
{
  const double length = boundaryLength(mesh, fans, inPatch, area);
  return area > 0.0 ? length / std::sqrt(area) : 0.0;
}

} // namespace

std::vector<char> bodyPatch(const SurfaceMesh& mesh, double share, int& centre, int candidates)
{
  centre = -1;
  std::vector<char> best;
  if (mesh.triangles.empty())
  {
    return best;
  }
  const auto graph = edgeGraph(mesh);
  const TriangleFans fans(mesh);
  std::vector<double> nearest = distancesFrom(graph, mesh.triangles[0][0]);
  double roundest = -1.0;
  for (int c = 0; c < candidates; ++c)
  {
    int candidate = -1;
    for (size_t v = 0; v < nearest.size(); ++v)
    {
      if (std::isfinite(nearest[v]) && (candidate < 0 || nearest[v] > nearest[candidate]))
      {
        candidate = static_cast<int>(v);
      }
    }
    if (candidate < 0 || nearest[candidate] == 0.0)
    {
      break;
    }
    std::vector<char> patch = growDiskPatchOn(mesh, fans, candidate, share);
    double area = 0.0;
    const double r = patch.empty() ? -1.0 : roundness(mesh, fans, patch, area);
    if (area >= BodyPatchReach * share * fans.total && r > roundest)
    {
      roundest = r;
      best.swap(patch);
      centre = candidate;
    }
    const std::vector<double> fromCandidate = distancesFrom(graph, candidate);
    for (size_t v = 0; v < nearest.size(); ++v)
    {
      nearest[v] = std::min(nearest[v], fromCandidate[v]);
    }
  }
  return best;
}

std::vector<char> growDiskPatch(const SurfaceMesh& mesh, int centre, double share)
{
  return growDiskPatchOn(mesh, TriangleFans(mesh), centre, share);
}

} // namespace otparam
