#include "Mesh/SurfaceMesh.h"

#include "Common/DirectedEdges.h"
#include "Common/IdList.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace otparam
{
namespace
{

struct UnionFind
{
  std::vector<int> parent;
  explicit UnionFind(size_t n)
    : parent(n)
  {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int i)
  {
    while (parent[i] != i)
    {
      i = parent[i] = parent[parent[i]];
    }
    return i;
  }
  bool unite(int a, int b)
  {
    a = find(a);
    b = find(b);
    if (a == b)
    {
      return false;
    }
    parent[a] = b;
    return true;
  }
};
} // namespace

double triangleArea(const SurfaceMesh& mesh, const Triangle& t)
{
  const Vec3 a = mesh.points[t[0]];
  return 0.5 * norm(cross(mesh.points[t[1]] - a, mesh.points[t[2]] - a));
}

std::string compactMesh(const std::vector<Vec3>& points,
  const std::vector<std::array<std::int64_t, 3>>& triangles, CompactedMesh& result)
{
  const auto n = static_cast<std::int64_t>(points.size());
  std::vector<std::int64_t> newId(points.size(), -1);
  // Every triangle with an id out of range is named (a file with wrong offsets has many).
  std::vector<size_t> outside;
  std::int64_t firstOutsideId = 0;
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    for (auto v : triangles[t])
    {
      if (v < 0 || v >= n)
      {
        firstOutsideId = outside.empty() ? v : firstOutsideId;
        outside.push_back(t);
        break;
      }
    }
  }
  if (!outside.empty())
  {
    std::ostringstream msg;
    msg << "triangle id(s) " << idList(outside) << " use point ids outside [0, " << n
        << "): triangle " << outside.front() << " uses point id " << firstOutsideId;
    return msg.str();
  }
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    const auto& tri = triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
    {
      std::ostringstream msg;
      msg << "triangle " << t << " uses point " << (tri[0] == tri[1] ? tri[0] : tri[2])
          << " twice (a degenerate triangle with zero area)";
      return msg.str();
    }
    for (auto v : tri)
    {
      newId[v] = 0;
    }
  }
  result = CompactedMesh();
  for (std::int64_t i = 0; i < n; ++i)
  {
    if (newId[i] < 0)
    {
      ++result.unreferencedPoints;
      continue;
    }
    if (result.mesh.points.size() >= static_cast<size_t>(std::numeric_limits<int>::max()))
    {
      return "the surface has too many points for 32-bit vertex indices";
    }
    newId[i] = static_cast<std::int64_t>(result.mesh.points.size());
    result.mesh.points.push_back(points[i]);
    result.originalPointIds.push_back(i);
  }
  result.mesh.triangles.reserve(triangles.size());
  for (const auto& tri : triangles)
  {
    result.mesh.triangles.push_back({ static_cast<int>(newId[tri[0]]),
      static_cast<int>(newId[tri[1]]), static_cast<int>(newId[tri[2]]) });
  }
  return {};
}

namespace
{
// The triangles' directed edges sorted by their undirected edge, the two directions of an edge
// side by side (a sorted array: several times faster than a hash map here), and from that, in
// one pass, the triangle across each triangle's edge: the fan walks and the boundary then take
// O(1) per step (a binary search per step took 2.5 s of the checks at 1M points).
class DirectedEdges
{
public:
  explicit DirectedEdges(const std::vector<Triangle>& triangles)
    : Across(3 * triangles.size(), -1)
  {
    this->Edges = sortedDirectedEdges(triangles);
    for (size_t e = 1; e < this->Edges.size(); ++e)
    {
      const std::uint64_t a = this->Edges[e - 1].first, b = this->Edges[e].first;
      if ((a >> 1) == (b >> 1) && a != b) // the two directions of one edge
      {
        this->Across[this->Edges[e - 1].second] = this->Edges[e].second / 3;
        this->Across[this->Edges[e].second] = this->Edges[e - 1].second / 3;
      }
    }
  }

  // A direction used twice (three or more triangles on one edge show up so too), or "".
  template <typename Id>
  std::string checkEachDirectionOnce(Id id, const std::vector<Triangle>& triangles) const
  {
    for (size_t e = 1; e < this->Edges.size(); ++e)
    {
      if (this->Edges[e].first == this->Edges[e - 1].first)
      {
        const int t = this->Edges[e].second / 3, k = this->Edges[e].second % 3;
        const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
        std::ostringstream msg;
        msg << "triangles " << this->Edges[e - 1].second / 3 << " and " << t
            << " both use the edge (" << id(a) << ", " << id(b)
            << ") in the same direction: the surface is non-manifold there or not "
               "consistently oriented (vtkPolyDataNormals with ConsistencyOn, ParaView's "
               "Generate Surface Normals, orients a manifold surface consistently)";
        return msg.str();
      }
    }
    return {};
  }

  // The triangle across edge k (from corner k to corner k + 1) of triangle t, or -1 on the
  // boundary. Meaningful once checkEachDirectionOnce passed.
  int across(int t, int k) const { return this->Across[3 * t + k]; }

private:
  std::vector<std::pair<std::uint64_t, int>> Edges; // sortedDirectedEdges
  std::vector<int> Across;
};

template <typename Id>
std::string checkCoordinatesAndAreas(const SurfaceMesh& mesh, Id id)
{
  std::ostringstream msg;
  std::vector<std::int64_t> bad;
  for (size_t v = 0; v < mesh.points.size(); ++v)
  {
    const Vec3 p = mesh.points[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    {
      bad.push_back(id(static_cast<int>(v)));
    }
  }
  if (!bad.empty())
  {
    msg << bad.size() << " point(s) have NaN or infinite coordinates: point ids " << idList(bad);
    return msg.str();
  }
  // Degenerate = area negligible against the square of the longest edge (a cap or needle
  // whose angles, and so the cotangent weights, are meaningless), or all points coincident.
  bool coincidentPoints = false, nearlyCoincidentPoints = false;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const Triangle& tri = mesh.triangles[t];
    const Vec3 a = mesh.points[tri[0]], b = mesh.points[tri[1]], c = mesh.points[tri[2]];
    const double shortest = std::min({ norm(b - a), norm(c - b), norm(a - c) });
    const double longest = std::max({ norm(b - a), norm(c - b), norm(a - c) });
    const double twiceArea = norm(cross(b - a, c - a));
    if (!(twiceArea > 1e-12 * longest * longest))
    {
      bad.push_back(static_cast<std::int64_t>(t));
      coincidentPoints = coincidentPoints || shortest == 0.0;
      nearlyCoincidentPoints = nearlyCoincidentPoints || shortest <= 1e-6 * longest;
    }
  }
  if (!bad.empty())
  {
    // Scans and exports often hold such triangles; say what removes them (measured: a face
    // with 95 edges collapsed to a point maps after the clean, 0.0105 / 25.4 degrees; VTK's
    // parametric ellipsoid, whose pole is several single-precision points 1e-8 apart, maps
    // after a clean with Tolerance 1e-6, 0.0006).
    msg << bad.size() << " triangle(s) have zero area (degenerate): triangle ids " << idList(bad);
    if (coincidentPoints)
    {
      msg << ". Some have coincident points: vtkCleanPolyData with ConvertPolysToLines off "
             "(ParaView: Clean, Convert Polys To Lines unchecked) merges them and drops the "
             "triangles that collapse";
    }
    else if (nearlyCoincidentPoints)
    {
      msg << ". Some have points almost at the same place (an edge under 1e-6 of the "
             "triangle's longest): vtkCleanPolyData with a small Tolerance, e.g. 1e-6 (ParaView: "
             "Clean, Tolerance), merges them and drops the triangles that collapse";
    }
    else
    {
      msg << ". Their points are collinear: collapse or flip them away first (e.g. CGAL's "
             "Polygon_mesh_processing::remove_degenerate_faces)";
    }
  }
  return msg.str();
}

// The triangles around every vertex must form one fan; "" or the first vertex that fails.
template <typename Id>
std::string checkManifoldVertices(const SurfaceMesh& mesh, const DirectedEdges& edges, Id id)
{
  const auto& tris = mesh.triangles;
  const size_t nv = mesh.points.size();
  std::vector<int> degree(nv, 0), fanStart(nv, -1);
  for (size_t t = 0; t < tris.size(); ++t)
  {
    for (int v : tris[t])
    {
      ++degree[v];
      fanStart[v] = static_cast<int>(t);
    }
  }
  auto corner = [&](int t, int v)
  {
    const auto& tri = tris[t];
    return tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
  };
  std::ostringstream msg;
  for (size_t v = 0; v < nv; ++v)
  {
    const int vi = static_cast<int>(v);
    if (degree[v] == 0)
    {
      msg << "point " << id(vi) << " belongs to no triangle (compact the mesh first)";
      return msg.str();
    }
    int visited = 1;
    // Around v one way: cross the edge (v, next) into the triangle that holds (next, v).
    const int start = fanStart[v];
    int t = start;
    bool closed = false;
    while (true)
    {
      t = edges.across(t, corner(t, vi)); // across the edge (v, next)
      if (t < 0 || t == start)
      {
        closed = t == start;
        break;
      }
      ++visited;
    }
    // An open fan: the other way from the start too.
    for (t = start; !closed;)
    {
      const int neighbour = edges.across(t, (corner(t, vi) + 2) % 3); // across (previous, v)
      if (neighbour < 0)
      {
        break;
      }
      t = neighbour;
      ++visited;
    }
    if (visited != degree[v])
    {
      msg << "point " << id(vi) << " is a non-manifold vertex: its " << degree[v]
          << " triangles do not form a single fan";
      return msg.str();
    }
  }
  return {};
}

size_t countComponents(const SurfaceMesh& mesh)
{
  UnionFind components(mesh.points.size());
  size_t count = mesh.points.size();
  for (const auto& t : mesh.triangles)
  {
    count -= components.unite(t[0], t[1]);
    count -= components.unite(t[1], t[2]);
  }
  return count;
}

// Points whose coordinates another point has too (all copies counted).
size_t countCoincidentPoints(const std::vector<Vec3>& points)
{
  std::vector<int> all(points.size());
  std::iota(all.begin(), all.end(), 0);
  const std::vector<char> coincident = coincidentAmong(points, all);
  return static_cast<size_t>(std::count(coincident.begin(), coincident.end(), 1));
}

// Boundary loops in the triangles' orientation: directed edges whose reverse is absent; with
// manifold vertices each boundary vertex has exactly one outgoing boundary edge.
std::vector<std::vector<int>> boundaryLoops(
  const SurfaceMesh& mesh, const DirectedEdges& edges, size_t& boundaryEdges)
{
  const size_t nv = mesh.points.size();
  std::vector<int> nextOnBoundary(nv, -1);
  boundaryEdges = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (edges.across(static_cast<int>(t), k) < 0)
      {
        nextOnBoundary[mesh.triangles[t][k]] = mesh.triangles[t][(k + 1) % 3];
        ++boundaryEdges;
      }
    }
  }
  std::vector<char> seen(nv, 0);
  std::vector<std::vector<int>> loops;
  for (size_t v = 0; v < nv; ++v)
  {
    if (nextOnBoundary[v] < 0 || seen[v])
    {
      continue;
    }
    std::vector<int> loop;
    for (int w = static_cast<int>(v); !seen[w]; w = nextOnBoundary[w])
    {
      seen[w] = 1;
      loop.push_back(w);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}
} // namespace

std::vector<char> coincidentAmong(const std::vector<Vec3>& points, const std::vector<int>& ids)
{
  auto coordinates = [&](size_t k)
  {
    const Vec3 p = points[ids[k]];
    return std::array<double, 3>{ p.x, p.y, p.z };
  };
  std::vector<size_t> order(ids.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(),
    [&](size_t a, size_t b) { return coordinates(a) < coordinates(b); });
  std::vector<char> coincident(ids.size(), 0);
  for (size_t i = 0; i + 1 < order.size(); ++i)
  {
    if (coordinates(order[i]) == coordinates(order[i + 1]))
    {
      coincident[order[i]] = coincident[order[i + 1]] = 1;
    }
  }
  return coincident;
}

std::string analyzeSurface(
  const SurfaceMesh& mesh, SurfaceTopology& topology, const std::vector<std::int64_t>* reportedIds)
{
  topology = SurfaceTopology();
  auto id = [reportedIds](int v) -> std::int64_t { return reportedIds ? (*reportedIds)[v] : v; };
  if (mesh.triangles.empty())
  {
    return "the surface has no triangles";
  }
  std::string error = checkCoordinatesAndAreas(mesh, id);
  if (!error.empty())
  {
    return error;
  }
  const DirectedEdges edges(mesh.triangles);
  error = edges.checkEachDirectionOnce(id, mesh.triangles);
  if (error.empty())
  {
    error = checkManifoldVertices(mesh, edges, id);
  }
  if (!error.empty())
  {
    return error;
  }
  topology.components = countComponents(mesh);
  if (topology.components > 1)
  {
    topology.coincidentPoints = countCoincidentPoints(mesh.points);
  }
  size_t boundaryEdges = 0;
  topology.boundaryLoops = boundaryLoops(mesh, edges, boundaryEdges);
  const size_t numberOfEdges = (3 * mesh.triangles.size() + boundaryEdges) / 2;
  topology.eulerCharacteristic = static_cast<long long>(mesh.points.size()) -
    static_cast<long long>(numberOfEdges) + static_cast<long long>(mesh.triangles.size());
  return {};
}

namespace
{
// What to try when a scan comes with debris (small separate pieces), or when its pieces are
// triangles that touch without sharing their points (an STL file read without merging them,
// an export split along its texture seams): there keeping the largest would keep a fragment.
std::string whatJoinsTheComponents(const SurfaceTopology& topology)
{
  if (topology.coincidentPoints == 0)
  {
    return " (to keep the largest: vtkPolyDataConnectivityFilter with "
           "SetExtractionModeToLargestRegion, ParaView's Connectivity with Extraction Mode "
           "'Extract Largest Region')";
  }
  std::ostringstream msg;
  msg << "; " << topology.coincidentPoints
      << " of its points lie exactly where another point is, so its triangles touch without "
         "sharing their points (a triangle soup, or a mesh split along seams): merge them with "
         "vtkCleanPolyData (ParaView: Clean) first";
  return msg.str();
}
} // namespace

std::string checkDiskTopology(const SurfaceMesh& mesh, std::vector<int>& boundaryLoop,
  const std::vector<std::int64_t>* reportedIds)
{
  boundaryLoop.clear();
  SurfaceTopology topology;
  const std::string error = analyzeSurface(mesh, topology, reportedIds);
  return error.empty() ? diskTopologyError(topology, boundaryLoop) : error;
}

std::string diskTopologyError(SurfaceTopology& topology, std::vector<int>& boundaryLoop)
{
  boundaryLoop.clear();
  std::ostringstream msg;
  const long long euler = topology.eulerCharacteristic;
  const size_t loops = topology.boundaryLoops.size();
  if (topology.components != 1)
  {
    msg << "the surface has " << topology.components
        << " connected components; a disk-like surface needs exactly 1"
        << whatJoinsTheComponents(topology);
  }
  else if (loops == 0)
  {
    msg << "the surface is closed (no boundary loop, Euler characteristic " << euler
        << "); a disk-like surface needs exactly 1 boundary loop (a closed genus-0 surface maps "
           "onto the sphere: vtkConformalSphereMap, or Domain Automatic or Sphere in "
           "vtkAreaPreservingParam)";
  }
  else if (loops > 1)
  {
    msg << "the surface has " << loops << " boundary loops; a disk-like surface needs exactly 1";
  }
  else if (euler != 1)
  {
    msg << "the surface has genus " << (1 - euler) / 2 << " (Euler characteristic " << euler
        << "); a disk-like surface has genus 0 (Euler characteristic 1)";
  }
  else
  {
    boundaryLoop = std::move(topology.boundaryLoops.front());
  }
  return msg.str();
}

std::string checkSphereTopology(
  const SurfaceMesh& mesh, const std::vector<std::int64_t>* reportedIds)
{
  SurfaceTopology topology;
  const std::string error = analyzeSurface(mesh, topology, reportedIds);
  return error.empty() ? sphereTopologyError(topology) : error;
}

std::string sphereTopologyError(const SurfaceTopology& topology)
{
  std::ostringstream msg;
  const long long euler = topology.eulerCharacteristic;
  const size_t loops = topology.boundaryLoops.size();
  if (topology.components != 1)
  {
    msg << "the surface has " << topology.components
        << " connected components; the sphere needs exactly 1 (one closed surface of genus 0)"
        << whatJoinsTheComponents(topology);
  }
  else if (loops > 0)
  {
    msg << "the surface has " << loops << " boundary loop" << (loops > 1 ? "s" : "")
        << "; the sphere needs a closed surface (use the Disk domain)";
  }
  else if (euler != 2)
  {
    msg << "the closed surface has genus " << (2 - euler) / 2 << " (Euler characteristic " << euler
        << "); the sphere needs genus 0 (Euler characteristic 2)";
  }
  return msg.str();
}

} // namespace otparam
