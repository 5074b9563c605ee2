#include "Mesh/HoleFilling.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <sstream>

namespace otparam
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

double loopLength(const SurfaceMesh& mesh, const std::vector<int>& loop)
{
  double length = 0.0;
  for (std::size_t k = 0; k < loop.size(); ++k)
  {
    length += norm(mesh.points[loop[(k + 1) % loop.size()]] - mesh.points[loop[k]]);
  }
  return length;
}

// Surface_mesh numbers vertices and faces in the order they are added, and appends what the
// hole filling adds: the input's ids stay valid.
Mesh toSurfaceMesh(const SurfaceMesh& mesh)
{
  Mesh out;
  out.reserve(static_cast<Mesh::size_type>(mesh.points.size()),
    static_cast<Mesh::size_type>(3 * mesh.triangles.size() / 2),
    static_cast<Mesh::size_type>(mesh.triangles.size()));
  for (const Vec3& p : mesh.points)
  {
    out.add_vertex(Kernel::Point_3(p.x, p.y, p.z));
  }
  for (const Triangle& t : mesh.triangles)
  {
    out.add_face(Mesh::Vertex_index(t[0]), Mesh::Vertex_index(t[1]), Mesh::Vertex_index(t[2]));
  }
  return out;
}

// The border halfedge (the one with no face) along the loop's first edge.
Mesh::Halfedge_index borderHalfedge(const Mesh& mesh, const std::vector<int>& loop)
{
  const Mesh::Vertex_index a(loop[0]), b(loop[1]);
  for (Mesh::Halfedge_index h : CGAL::halfedges_around_target(a, mesh))
  {
    if (mesh.source(h) == b && mesh.is_border(h))
    {
      return h;
    }
    const Mesh::Halfedge_index o = mesh.opposite(h);
    if (mesh.target(o) == b && mesh.is_border(o))
    {
      return o;
    }
  }
  return Mesh::null_halfedge();
}
// Per boundary point (loops' order): whether another boundary point has exactly its
// coordinates.
std::vector<std::vector<char>> coincidentOnBoundary(
  const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops)
{
  std::vector<int> boundary;
  for (const std::vector<int>& loop : loops)
  {
    boundary.insert(boundary.end(), loop.begin(), loop.end());
  }
  const std::vector<char> flags = coincidentAmong(mesh.points, boundary);
  std::vector<std::vector<char>> coincident;
  auto next = flags.begin();
  for (const std::vector<int>& loop : loops)
  {
    coincident.emplace_back(next, next + static_cast<std::ptrdiff_t>(loop.size()));
    next += static_cast<std::ptrdiff_t>(loop.size());
  }
  return coincident;
}

// "" or why loop k is no hole: a slit, most of its points lying exactly on other boundary
// points (a seam whose points the triangles on its two sides do not share, as exports split
// along texture seams). Filled, such a loop gets triangles of zero area (measured: a face
// with a 99-point slit mapped with the transport stalled at relative error 3.6, mean |log area
// ratio| 0.26).
std::string slitInstead(const std::vector<int>& loop, const std::vector<char>& coincident,
  std::size_t k, std::int64_t firstPoint)
{
  const auto count = static_cast<std::size_t>(std::count(coincident.begin(), coincident.end(), 1));
  if (2 * count < loop.size())
  {
    return {};
  }
  std::ostringstream msg;
  msg << "boundary loop " << k + 1 << " (" << loop.size() << " edges, through point " << firstPoint
      << ") is a slit, not a hole: " << count
      << " of its points lie exactly where other boundary points are, so the surface is split "
         "along a seam whose points its triangles do not share (as exports split along texture "
         "seams): merge them with vtkCleanPolyData (ParaView: Clean) first";
  return msg.str();
}
std::int64_t reported(int v, const std::vector<std::int64_t>* reportedIds)
{
  return reportedIds ? (*reportedIds)[v] : v;
}
} // namespace

std::string slitAmongHoles(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops,
  std::size_t kept, const std::vector<std::int64_t>* reportedIds)
{
  const std::vector<std::vector<char>> coincident = coincidentOnBoundary(mesh, loops);
  for (std::size_t k = 0; k < loops.size(); ++k)
  {
    const std::string slit = k == kept
      ? std::string()
      : slitInstead(loops[k], coincident[k], k, reported(loops[k][0], reportedIds));
    if (!slit.empty())
    {
      return slit;
    }
  }
  return {};
}

double largestHoleFraction(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops)
{
  if (loops.empty())
  {
    return 0.0;
  }
  double surfaceArea = 0.0;
  for (const Triangle& t : mesh.triangles)
  {
    surfaceArea += triangleArea(mesh, t);
  }
  const double length = loopLength(mesh, loops[longestLoop(mesh, loops)]);
  return length * length / (4.0 * 3.14159265358979323846) / surfaceArea;
}

std::size_t longestLoop(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops)
{
  std::size_t longest = 0;
  double longestLength = -1.0;
  for (std::size_t k = 0; k < loops.size(); ++k)
  {
    const double length = loopLength(mesh, loops[k]);
    if (length > longestLength)
    {
      longest = k;
      longestLength = length;
    }
  }
  return longest;
}

std::string fillHolesButLongest(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops,
  FilledSurface& filled, const std::vector<std::int64_t>* reportedIds)
{
  const std::size_t kept = longestLoop(mesh, loops);
  const std::string error = fillHoles(mesh, loops, kept, filled, reportedIds);
  if (error.empty())
  {
    filled.boundaryLoop = loops[kept];
  }
  return error;
}

std::string fillHoles(const SurfaceMesh& mesh, const std::vector<std::vector<int>>& loops,
  std::size_t kept, FilledSurface& filled, const std::vector<std::int64_t>* reportedIds)
{
  filled = FilledSurface();
  const std::string slit = slitAmongHoles(mesh, loops, kept, reportedIds);
  if (!slit.empty())
  {
    return slit;
  }
  Mesh cgalMesh = toSurfaceMesh(mesh);
  for (std::size_t k = 0; k < loops.size(); ++k)
  {
    if (k == kept)
    {
      continue;
    }
    const Mesh::Halfedge_index h = borderHalfedge(cgalMesh, loops[k]);
    std::vector<Mesh::Face_index> faces;
    if (h != Mesh::null_halfedge())
    {
      // Fairing may fail (its linear system singular on a degenerate rim); the refined
      // patch it leaves is still a valid fill, which is all the computation needs.
      PMP::triangulate_refine_and_fair_hole(cgalMesh, h, std::back_inserter(faces),
        CGAL::Emptyset_iterator(), CGAL::parameters::fairing_continuity(1));
    }
    if (faces.empty())
    {
      std::ostringstream msg;
      msg << "the hole along boundary loop " << k + 1 << " (" << loops[k].size()
          << " edges, through point " << reported(loops[k][0], reportedIds)
          << ") could not be closed";
      return msg.str();
    }
    ++filled.filledHoles;
  }
  filled.mesh.points = mesh.points;
  filled.mesh.triangles = mesh.triangles;
  for (Mesh::Vertex_index v : cgalMesh.vertices())
  {
    if (static_cast<std::size_t>(v) >= mesh.points.size())
    {
      const Kernel::Point_3& p = cgalMesh.point(v);
      filled.mesh.points.push_back({ p.x(), p.y(), p.z() });
    }
  }
  double inputArea = 0.0, fillArea = 0.0;
  for (const Triangle& t : mesh.triangles)
  {
    inputArea += triangleArea(mesh, t);
  }
  for (Mesh::Face_index f : cgalMesh.faces())
  {
    if (static_cast<std::size_t>(f) < mesh.triangles.size())
    {
      continue;
    }
    Triangle t;
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(cgalMesh.halfedge(f), cgalMesh))
    {
      t[k++] = static_cast<int>(v);
    }
    filled.mesh.triangles.push_back(t);
    fillArea += triangleArea(filled.mesh, t);
  }
  filled.fillAreaFraction = fillArea / (inputArea + fillArea);
  return {};
}

} // namespace otparam
